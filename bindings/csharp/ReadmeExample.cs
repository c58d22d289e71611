using Legwork;

static class ReadmeExample
{
    static void Main(string[] args)
    {
        using (var db = Database.Load(args[0]))                        // legwork accent build ... --out X.lwdb
        using (var model = Model.CreateAccent(db, AccentSettings.Default()))
        using (var avatar = Avatar.Create(model))
        {
            var rotations = new double[4 * avatar.JointCount];         // w,x,y,z per joint, local
            var positions = new double[3 * avatar.JointCount];         // metres, world
            foreach (Frame recorded in Tracker.FramesFromBvh("data/cmu/bvh/walking/07_02.bvh", 90, true))
            {
                Frame frame = recorded;                                 // in Unity: head + controllers each frame
                avatar.Update(ref frame);
                avatar.GetPose(rotations, null, positions);
            }
            Convert.Positions(Engine.Unity, true, positions);          // Unity: left-handed, y up, metres
            System.Console.WriteLine("{0} {1} at {2:F3} m", model.Skeleton.JointName(0), model.HumanoidName(0, false), positions[1]);
        }
    }
}
