// The walker's settings through Legwork.cs (issue 14): the defaults, a ramp
// ground on which the planted foot stays on the ground, stairs climbed with
// the feet on the treads, and a bad ground refused naming the field. Run by CTest (csharp.walker_ground).
//   mono walkerground.exe WALK.json
using System;
using Legwork;

static class WalkerGround
{
    static int Joint(Model model, string humanoid)
    {
        int n = model.Skeleton.JointCount;
        for (int j = 0; j < n; ++j)
            if (model.HumanoidName(j, false) == humanoid) return j;
        throw new Exception("the walk's skeleton has no " + humanoid);
    }

    // The ramp: 10 % up along +z from z = 0.5 m (flat before it).
    const double Grade = 0.1, RampStart = 0.5;
    static double Ground(double z) { return Grade * Math.Max(0.0, z - RampStart); }

    // Walks 5 s straight ahead (+z); returns the mean over the last second of the
    // lowest foot joint's (ankle or toes) height above the ramp's ground under it,
    // and the left ankle's mean z then.
    static double Clearance(Model model, out double endZ) { return ClearanceOn(model, Ground, out endZ); }

    // The same over any ground (its height at z).
    static double ClearanceOn(Model model, Func<double, double> ground, out double endZ)
    {
        Avatar avatar = Avatar.Create(model);
        int[] ankle = { Joint(model, "LeftFoot"), Joint(model, "RightFoot") };
        int[] foot = { ankle[0], ankle[1], Joint(model, "LeftToes"), Joint(model, "RightToes") };
        double[] world = new double[3 * avatar.JointCount];
        Frame f = new Frame();
        f.Head.Y = 1.7;
        f.Head.Qw = 1;
        f.Head.Valid = 1;
        double sum = 0, sumZ = 0;
        int n = 0;
        const int frames = 150;
        for (int i = 0; i < frames; ++i)
        {
            f.Time = i / 30.0;
            avatar.Update(ref f);
            avatar.GetPose(null, null, world);
            if (i < frames - 30) continue;
            double lowest = double.MaxValue;
            foreach (int a in foot)
                lowest = Math.Min(lowest, world[3 * a + 1] - ground(world[3 * a + 2]));
            sum += lowest;
            sumZ += world[3 * ankle[0] + 2];
            ++n;
        }
        avatar.Dispose();
        endZ = sumZ / n;
        return sum / n;
    }

    // Horizontal distance from the left ankle to the left toes in the first pose.
    static double FootLength(Model model)
    {
        Avatar avatar = Avatar.Create(model);
        double[] world = new double[3 * avatar.JointCount];
        Frame f = new Frame();
        f.Head.Y = 1.7;
        f.Head.Qw = 1;
        f.Head.Valid = 1;
        avatar.Update(ref f);
        avatar.GetPose(null, null, world);
        avatar.Dispose();
        int a = Joint(model, "LeftFoot"), t = Joint(model, "LeftToes");
        return Math.Sqrt(Math.Pow(world[3 * t] - world[3 * a], 2) + Math.Pow(world[3 * t + 2] - world[3 * a + 2], 2));
    }

    static int Main(string[] args)
    {
        if (args.Length != 1)
        {
            Console.Error.WriteLine("usage: walkerground WALK.json");
            return 2;
        }
        Library.CheckAbi();
        WalkerSettings s = WalkerSettings.Default();
        Expect.That("defaults", s.Root == WalkerRoot.Smooth && s.GroundJson == null && s.SoftReach > 0 && s.SoftReach <= 1,
               "root " + s.Root + ", soft reach " + s.SoftReach + ", max turn " + s.MaxTurnPerStep);
        double flatZ, rampZ;
        Model flat = Model.CreateWalker(args[0], s);
        s.GroundJson = "{\"slope\": {\"origin\": [0, " + RampStart + "], \"direction\": [0, 1], \"grade\": " + Grade + "}}";
        Model ramp = Model.CreateWalker(args[0], s);
        double flatBelowRamp = Clearance(flat, out flatZ), onRamp = Clearance(ramp, out rampZ), flatEndZ;
        double onFloor = ClearanceOn(flat, z => 0.0, out flatEndZ);
        double onFlat = flatBelowRamp + Ground(flatZ);
        Expect.That("walked up the ramp", Ground(rampZ) > 0.25, string.Format("left ankle at z {0:F2} m, ground {1:F3} m", rampZ, Ground(rampZ)));
        Expect.That("the flat walker's feet end below the ramp", flatBelowRamp < -0.2, string.Format("{0:F3} m", flatBelowRamp));
        // On the ramp the leg IK plants the feet on it: the lowest foot joint as high
        // above it as above the floor, within grade x the foot's length (a joint
        // that far from the contact sees the slope's rise).
        double footLength = FootLength(flat);
        Expect.That("planted foot as high above the ramp as above the floor", Math.Abs(onRamp - onFlat) <= Grade * footLength,
               string.Format("{0:F3} m above the floor, {1:F3} m above the ramp (bound {2:F3} m)", onFlat, onRamp, Grade * footLength));
        flat.Dispose();
        ramp.Dispose();

        // Stairs (the shipped stairs.json's flight: 5 x 0.15 m from z = 1.5 m,
        // 0.36 m treads): each foot planted flat on a tread, so the lowest foot
        // joint ends as high above the landing as it was above the floor.
        WalkerSettings st = WalkerSettings.Default();
        st.GroundJson = "{\"stairs\": {\"origin\": [0, 1.5], \"direction\": [0, 1], \"rise\": 0.15, \"run\": 0.36, \"count\": 5}}";
        Model stairs = Model.CreateWalker(args[0], st);
        double stairsZ;
        double aboveLanding = ClearanceOn(stairs, z => z < 1.5 ? 0.0 : 0.15 * Math.Min(5, Math.Floor((z - 1.5) / 0.36) + 1), out stairsZ);
        Expect.That("climbed the stairs", stairsZ > 1.5 + 5 * 0.36, string.Format("left ankle at z {0:F2} m", stairsZ));
        // (Within issue 14's 2 mm for feet on the ground.)
        Expect.That("feet as high above the landing as above the floor", Math.Abs(aboveLanding - onFloor) <= 0.002,
                    string.Format("{0:F4} m above the floor, {1:F4} m above the landing", onFloor, aboveLanding));
        stairs.Dispose();

        WalkerSettings bad = WalkerSettings.Default();
        bad.GroundJson = "{\"slope\": {\"origin\": [0, 0.5], \"direction\": [0, 1], \"grade\": 0.5}}";
        Expect.Throws<LegworkException>("too steep a ramp refused", () => Model.CreateWalker(args[0], bad),
                                        "lw_walker_settings.ground_json: slope: grade");
        bad = WalkerSettings.Default();
        bad.StairsCadence = 1.5;
        Expect.Throws<LegworkException>("stairs cadence above 1 refused", () => Model.CreateWalker(args[0], bad), "stairs_cadence must be in (0, 1]");
        bad = WalkerSettings.Default();
        bad.SoftReach = 0;
        Expect.Throws<LegworkException>("soft reach 0 refused", () => Model.CreateWalker(args[0], bad), "soft_reach must be in (0, 1]");
        return Expect.Summary("walkerground");
    }
}
