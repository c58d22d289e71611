// Bad input through Legwork.cs must give exceptions with clear messages, never
// a crash: run by CTest (csharp.checks) with a database and a trial.
//   mono checks.exe DATABASE.lwdb TRIAL.bvh NOT_A_DATABASE
using System;
using Legwork;

static class Checks
{
    static int Main(string[] args)
    {
        if (args.Length != 3)
        {
            Console.Error.WriteLine("usage: checks DATABASE.lwdb TRIAL.bvh NOT_A_DATABASE");
            return 2;
        }
        Library.CheckAbi();
        Expect.Throws<LegworkException>("missing database", () => Database.Load(args[0] + ".missing"), ".missing");
        Expect.Throws<LegworkException>("not a database", () => Database.Load(args[2]), "not a legwork accent database");
        Expect.Throws<LegworkException>("missing trial", () => Tracker.FramesFromBvh(args[1] + ".missing", 90, true), ".missing");
        Database db = Database.Load(args[0]);
        Expect.That("database classes", db.ClassCount > 0 && db.ClassName(0) != null && db.ClassName(db.ClassCount) == null,
               db.ClassCount + " classes, first " + db.ClassName(0));
        AccentSettings bad = AccentSettings.Default();
        bad.Classes = "walking,flying";
        Expect.Throws<LegworkException>("unknown class", () => Model.CreateAccent(db, bad), "flying");
        bad = AccentSettings.Default();
        bad.K = 0;
        Expect.Throws<LegworkException>("k out of range", () => Model.CreateAccent(db, bad), "k must be");
        bad = AccentSettings.Default();
        Expect.That("foot lift default", bad.FootLiftHeight > 0, "FootLiftHeight " + bad.FootLiftHeight);
        Expect.That("foot slack default", bad.FootLockSlack == 0, "FootLockSlack " + bad.FootLockSlack);
        Expect.That("swing speed default", bad.FootSwingSpeed > 0, "FootSwingSpeed " + bad.FootSwingSpeed);
        bad.FootLiftHeight = 0.9;
        Expect.Throws<LegworkException>("foot lift out of range", () => Model.CreateAccent(db, bad), "foot_lift_height must be between 0 and 0.5 metres");
        bad = AccentSettings.Default();
        Expect.That("travel weight default", bad.TravelWeight == 2, "TravelWeight " + bad.TravelWeight);
        bad.TravelWeight = -1;
        Expect.Throws<LegworkException>("travel weight out of range", () => Model.CreateAccent(db, bad), "travel_weight must be between 0 and 100 (0 = off)");
        bad = AccentSettings.Default();
        Expect.That("head height gate default", bad.MaxHeadHeightDiff == 0.15, "MaxHeadHeightDiff " + bad.MaxHeadHeightDiff);
        bad.MaxHeadHeightDiff = 3;
        Expect.Throws<LegworkException>("head height gate out of range", () => Model.CreateAccent(db, bad), "max_head_height_diff must be between 0 and 2");
        bad = AccentSettings.Default();
        Expect.That("smoothing feedforward default", bad.SmoothFeedforward == 1, "SmoothFeedforward " + bad.SmoothFeedforward);
        bad.SmoothFeedforward = 1.5;
        Expect.Throws<LegworkException>("smoothing feedforward out of range", () => Model.CreateAccent(db, bad), "smooth_feedforward must be between 0 and 1");
        bad = AccentSettings.Default();
        Expect.That("lying root smoothing default", bad.LyingRootSmoothing == 8, "LyingRootSmoothing " + bad.LyingRootSmoothing);
        bad.LyingRootSmoothing = 0.5;
        Expect.Throws<LegworkException>("lying root smoothing out of range", () => Model.CreateAccent(db, bad), "lying_root_smoothing must be between 1 and 20");
        bad = AccentSettings.Default();
        Expect.That("lying crown default", bad.LyingCrown == 1, "LyingCrown " + bad.LyingCrown);
        bad.LyingCrown = -0.5;
        Expect.Throws<LegworkException>("lying crown out of range", () => Model.CreateAccent(db, bad), "lying_crown must be between 0 and 1");
        bad = AccentSettings.Default();
        Expect.That("other class cost default", bad.OtherClassCost == 1.25, "OtherClassCost " + bad.OtherClassCost);
        bad.OtherClassCost = 0.5;
        Expect.Throws<LegworkException>("other class cost out of range", () => Model.CreateAccent(db, bad), "other_class_cost must be 0 (search only the classes to match) or a factor from 1 to 1e6");
        bad = AccentSettings.Default();
        Expect.That("search interval default", bad.SearchInterval == 0.044, "SearchInterval " + bad.SearchInterval);
        bad.SearchInterval = 1.5;
        Expect.Throws<LegworkException>("search interval out of range", () => Model.CreateAccent(db, bad), "search_interval must be between 0 and 1 second (0 = search every frame)");
        bad = AccentSettings.Default();
        Expect.That("floor default", bad.Floor == 1 && bad.FloorHeight == 0, "Floor " + bad.Floor + ", FloorHeight " + bad.FloorHeight);
        bad.FloorHeight = 12;
        Expect.Throws<LegworkException>("floor height out of range", () => Model.CreateAccent(db, bad), "floor_height must be between -10 and 10 metres");
        bad = AccentSettings.Default();
        Expect.That("foot lock hold default", bad.FootLockHoldSeconds == 0.2, "FootLockHoldSeconds " + bad.FootLockHoldSeconds);
        bad.FootLockHoldSeconds = 11;
        Expect.Throws<LegworkException>("foot lock hold out of range", () => Model.CreateAccent(db, bad), "foot_lock_hold_seconds must be between 0 and 10 s");

        Model model = Model.CreateAccent(db, AccentSettings.Default());
        Avatar avatar = Avatar.Create(model);
        Frame[] frames = Tracker.FramesFromBvh(args[1], 90, true);
        Expect.That("first frame", avatar.Update(ref frames[0]) == Status.Ok, "frames: " + frames.Length);
        Frame stale = frames[0];
        Expect.That("repeated time rejected", avatar.Update(ref stale) == Status.Rejected, "");
        Frame lost = frames[1];
        lost.LeftHand.X = double.NaN;
        Expect.That("NaN hand degrades", avatar.Update(ref lost) == Status.Degraded, "");
        Frame nan = frames[2];
        nan.Time = double.NaN;
        Expect.That("NaN time rejected", avatar.Update(ref nan) == Status.Rejected, "");
        Expect.Throws<ArgumentException>("short pose array", () => avatar.GetPose(new double[3], null, null), "localRotations needs");
        // The frame's figures, by the server's pose "info" names: the recognised class is one of the database's.
        for (int i = 3; i < 60; ++i) avatar.Update(ref frames[i]);
        var info = avatar.Info;
        int active = (int)avatar.InfoNumber("active_class");
        Expect.That("recognised class", active >= 0 && active < db.ClassCount && db.ClassName(active) != null, "active_class " + active);
        // A frame that searched covers 1..all classes; one that continued its matches (SearchInterval), none.
        bool didSearch = avatar.InfoNumber("searched") == 1;
        double searched = avatar.InfoNumber("classes_searched");
        Expect.That("classes searched", didSearch ? searched >= 1 && searched <= db.ClassCount : searched == 0,
                    "classes_searched " + searched + ", searched " + didSearch);
        string match = avatar.InfoText("match");
        Expect.That("match status", match == "matched" || match == "partial" || match == "unmatched", "match '" + match + "'");
        Expect.That("info fields", info.Count == 8 && info.ContainsKey("match_weight") && (string)info["match"] == match,
                    info.Count + " fields");
        Expect.Throws<LegworkException>("unknown info field", () => avatar.InfoNumber("speed"),
                                        "no field 'speed' (this avatar's: match, match_weight");
        Expect.Throws<LegworkException>("text info field as a number", () => avatar.InfoNumber("match"), "is a text");
        avatar.Reset();
        Expect.Throws<LegworkException>("info after a reset", () => avatar.InfoNumber("match_weight"), "no frame consumed yet");
        string hips = model.HumanoidName(0, false);
        Expect.That("humanoid name of the root", hips == "Hips", "'" + hips + "'");

        // Disposal: a model and its database outlive their users' Dispose calls; a
        // disposed handle raises ObjectDisposedException instead of reaching C.
        db.Dispose();
        model.Dispose();
        Expect.That("avatar alive after its model and database were disposed", avatar.Update(ref frames[3]) >= 0, "");
        avatar.Dispose();
        Expect.Throws<ObjectDisposedException>("disposed avatar", () => avatar.Update(ref frames[4]), "");
        return Expect.Summary("checks");
    }
}
