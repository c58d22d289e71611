// legwork from C#: what examples/c/main.c does, through Legwork.cs. Loads an
// accentuation database, drives one avatar with a CMU trial's head and hands
// (as a headset and two controllers would) and writes every frame's pose as
// CSV: frame,status,joint,qw,qx,qy,qz,x,y,z (local rotation, world position,
// numbers as C's "%.17g"), so CI can compare it byte for byte with the C run.
//
//   legwork accent build --data data/cmu --exclude bvh/walking/07_02.bvh --out sample.lwdb
//   mcs -r:System.Numerics -out:example.exe Example.cs Legwork.cs
//   LD_LIBRARY_PATH=build/src/capi mono example.exe sample.lwdb data/cmu/bvh/walking/07_02.bvh poses.csv
using System;
using System.Globalization;
using System.IO;
using System.Numerics;
using System.Text;
using Legwork;

static class Example
{
    static readonly BigInteger Ten16 = BigInteger.Pow(10, 16), Ten17 = BigInteger.Pow(10, 17);

    // C's printf("%.17g") exactly: the double's exact value (BigInteger) rounded
    // to 17 significant digits, ties to even as glibc does. (.NET's "G17" rounds
    // exact ties up, which differs in the last digit for a few large values.)
    public static string G17(double v)
    {
        if (double.IsNaN(v)) return "nan";
        if (double.IsInfinity(v)) return v > 0 ? "inf" : "-inf";
        long bits = BitConverter.DoubleToInt64Bits(v);
        string sign = bits < 0 ? "-" : "";
        int exp = (int)((bits >> 52) & 0x7FF);
        long mantissa = bits & 0xFFFFFFFFFFFFFL;
        if (exp == 0 && mantissa == 0) return sign + "0";
        if (exp == 0) exp = 1; else mantissa |= 1L << 52;
        exp -= 1075; // |v| = mantissa * 2^exp exactly
        BigInteger num = mantissa, den = BigInteger.One;
        if (exp > 0) num <<= exp; else den <<= -exp;
        int e10 = (int)Math.Floor(Math.Log10(Math.Abs(v)));
        BigInteger q, r;
        while (true) // q = 17 significant digits of |v| / 10^(e10 - 16)
        {
            int shift = 16 - e10;
            BigInteger n = shift >= 0 ? num * BigInteger.Pow(10, shift) : num;
            BigInteger d = shift >= 0 ? den : den * BigInteger.Pow(10, -shift);
            q = BigInteger.DivRem(n, d, out r);
            if (q >= Ten17) { ++e10; continue; }
            if (q < Ten16) { --e10; continue; }
            int c = (r * 2).CompareTo(d);
            if (c > 0 || (c == 0 && !q.IsEven)) q += 1;
            if (q == Ten17) { q = Ten16; ++e10; }
            break;
        }
        string digits = q.ToString(CultureInfo.InvariantCulture);
        if (e10 < -4 || e10 >= 17)
        {
            string frac = digits.Substring(1).TrimEnd('0');
            string e = (e10 < 0 ? "-" : "+") + Math.Abs(e10).ToString("00", CultureInfo.InvariantCulture);
            return sign + digits[0] + (frac.Length > 0 ? "." + frac : "") + "e" + e;
        }
        string whole, fraction;
        if (e10 >= 0) { whole = digits.Substring(0, e10 + 1); fraction = digits.Substring(e10 + 1); }
        else { whole = "0"; fraction = new string('0', -e10 - 1) + digits; }
        fraction = fraction.TrimEnd('0');
        return sign + whole + (fraction.Length > 0 ? "." + fraction : "");
    }

    static int Main(string[] args)
    {
        if (args.Length != 3)
        {
            Console.Error.WriteLine("usage: example DATABASE.lwdb TRIAL.bvh OUT.csv");
            return 2;
        }
        try
        {
            Library.CheckAbi();
            using (Database db = Database.Load(args[0]))
            {
                Frame[] frames = Tracker.FramesFromBvh(args[1], 90.0, true);
                AccentSettings settings = AccentSettings.Default();
                settings.UserHeight = 1.7;
                using (Model model = Model.CreateAccent(db, settings))
                using (Avatar avatar = Avatar.Create(model))
                using (StreamWriter output = new StreamWriter(args[2], false, new UTF8Encoding(false)))
                {
                    output.NewLine = "\n";
                    int joints = avatar.JointCount;
                    double[] rotations = new double[4 * joints];
                    double[] positions = new double[3 * joints];
                    StringBuilder line = new StringBuilder();
                    for (int f = 0; f < frames.Length; ++f)
                    {
                        Status s = avatar.Update(ref frames[f]);
                        avatar.GetPose(rotations, null, positions);
                        string name = Library.StatusName(s);
                        for (int j = 0; j < joints; ++j)
                        {
                            line.Clear();
                            line.Append(f).Append(',').Append(name).Append(',').Append(j);
                            for (int i = 0; i < 4; ++i) line.Append(',').Append(G17(rotations[4 * j + i]));
                            for (int i = 0; i < 3; ++i) line.Append(',').Append(G17(positions[3 * j + i]));
                            output.WriteLine(line.ToString());
                        }
                    }
                    Console.WriteLine("example_cs: {0} frames x {1} joints written to {2}", frames.Length, joints, args[2]);
                }
            }
            return 0;
        }
        catch (LegworkException e)
        {
            Console.Error.WriteLine("example_cs: {0} ({1})", e.Message, Library.StatusName(e.Status));
            return 1;
        }
    }
}
