// Bad input through Legwork.cs must give exceptions with clear messages, never
// a crash: run by CTest (csharp.checks) with a database and a trial.
//   mono checks.exe DATABASE.lwdb TRIAL.bvh NOT_A_DATABASE
using System;
using Legwork;

static class Checks
{
    static int failures;

    static void Expect(string what, bool ok, string detail)
    {
        Console.WriteLine("{0}: {1} ({2})", ok ? "ok  " : "FAIL", what, detail);
        if (!ok) ++failures;
    }

    // Runs `action`, expecting an exception of type T whose message contains `text`.
    static void Throws<T>(string what, Action action, string text) where T : Exception
    {
        try
        {
            action();
            Expect(what, false, "no exception");
        }
        catch (T e)
        {
            Expect(what, e.Message.Contains(text), e.GetType().Name + ": " + e.Message);
        }
    }

    static int Main(string[] args)
    {
        if (args.Length != 3)
        {
            Console.Error.WriteLine("usage: checks DATABASE.lwdb TRIAL.bvh NOT_A_DATABASE");
            return 2;
        }
        Library.CheckAbi();
        Throws<LegworkException>("missing database", () => Database.Load(args[0] + ".missing"), ".missing");
        Throws<LegworkException>("not a database", () => Database.Load(args[2]), "not a legwork accent database");
        Throws<LegworkException>("missing trial", () => Tracker.FramesFromBvh(args[1] + ".missing", 90, true), ".missing");
        Database db = Database.Load(args[0]);
        Expect("database classes", db.ClassCount > 0 && db.ClassName(0) != null && db.ClassName(db.ClassCount) == null,
               db.ClassCount + " classes, first " + db.ClassName(0));
        AccentSettings bad = AccentSettings.Default();
        bad.Classes = "walking,flying";
        Throws<LegworkException>("unknown class", () => Model.CreateAccent(db, bad), "flying");
        bad = AccentSettings.Default();
        bad.K = 0;
        Throws<LegworkException>("k out of range", () => Model.CreateAccent(db, bad), "k must be");
        bad = AccentSettings.Default();
        Expect("foot lift default", bad.FootLiftHeight > 0, "FootLiftHeight " + bad.FootLiftHeight);
        Expect("foot slack default", bad.FootLockSlack == 0, "FootLockSlack " + bad.FootLockSlack);
        Expect("swing speed default", bad.FootSwingSpeed > 0, "FootSwingSpeed " + bad.FootSwingSpeed);
        bad.FootLiftHeight = 0.9;
        Throws<LegworkException>("foot lift out of range", () => Model.CreateAccent(db, bad), "foot_lift_height must be between 0 and 0.5 metres");

        Model model = Model.CreateAccent(db, AccentSettings.Default());
        Avatar avatar = Avatar.Create(model);
        Frame[] frames = Tracker.FramesFromBvh(args[1], 90, true);
        Expect("first frame", avatar.Update(ref frames[0]) == Status.Ok, "frames: " + frames.Length);
        Frame stale = frames[0];
        Expect("repeated time rejected", avatar.Update(ref stale) == Status.Rejected, "");
        Frame lost = frames[1];
        lost.LeftHand.X = double.NaN;
        Expect("NaN hand degrades", avatar.Update(ref lost) == Status.Degraded, "");
        Frame nan = frames[2];
        nan.Time = double.NaN;
        Expect("NaN time rejected", avatar.Update(ref nan) == Status.Rejected, "");
        Throws<ArgumentException>("short pose array", () => avatar.GetPose(new double[3], null, null), "localRotations needs");
        string hips = model.HumanoidName(0, false);
        Expect("humanoid name of the root", hips == "Hips", "'" + hips + "'");

        // Disposal: a model and its database outlive their users' Dispose calls; a
        // disposed handle raises ObjectDisposedException instead of reaching C.
        db.Dispose();
        model.Dispose();
        Expect("avatar alive after its model and database were disposed", avatar.Update(ref frames[3]) >= 0, "");
        avatar.Dispose();
        Throws<ObjectDisposedException>("disposed avatar", () => avatar.Update(ref frames[4]), "");
        Console.WriteLine(failures == 0 ? "checks: all passed" : "checks: " + failures + " failed");
        return failures == 0 ? 0 : 1;
    }
}
