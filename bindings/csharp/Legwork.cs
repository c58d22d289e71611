// legwork for C# (Unity, or any .NET/Mono): the P/Invoke layer over the C API
// (include/legwork/legwork.h). Drop this file and liblegwork (liblegwork.so,
// legwork.dll or liblegwork.dylib) into a Unity project's Assets/Plugins.
//
// Shape: one SafeHandle per C handle (Database, Skeleton, Model, Avatar), so
// handles are released exactly once, also from the finalizer, and a model keeps
// its database alive (an avatar its model) for as long as it lives. A negative
// lw_status becomes a LegworkException carrying lw_last_error()'s message.
// Per frame, Avatar.Update(ref Frame) and Avatar.GetPose(...) pass blittable
// structs and caller-owned arrays: no managed allocation.
//
// Units and frames: metres, seconds, legwork's world frame (right-handed, y up,
// faces +z, +x is the character's left); quaternions are (w, x, y, z). Convert
// to Unity's frame with Legwork.Convert.Positions/Rotations(Engine.Unity, ...).
using System;
using System.Runtime.InteropServices;

namespace Legwork
{
    /// <summary>lw_status: results of the C API (negative = error).</summary>
    public enum Status
    {
        Ok = 0,
        Degraded = 1,
        Rejected = 2,
        Restarted = 3,
        InvalidArgument = -1,
        Io = -2,
        Format = -3,
        OutOfMemory = -4,
        Unsupported = -5,
        Internal = -6,
    }

    /// <summary>lw_method: which runtime a model drives.</summary>
    public enum Method { Accent = 0, Ik = 1, Wip = 2, Walker = 3 }

    /// <summary>lw_engine: target frames of Convert.</summary>
    public enum Engine { Legwork = 0, Unity = 1, Unreal = 2, Godot = 3 }

    /// <summary>A failed legwork call: Status and lw_last_error()'s message.</summary>
    public class LegworkException : Exception
    {
        public Status Status { get; private set; }

        public LegworkException(Status status, string message) : base(message) { Status = status; }
    }

    /// <summary>lw_device: one tracked device (world position in metres, rotation w,x,y,z).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Device
    {
        public double X, Y, Z;
        public double Qw, Qx, Qy, Qz;
        public int Valid;

        public Device(double x, double y, double z, double qw, double qx, double qy, double qz)
        {
            X = x; Y = y; Z = z; Qw = qw; Qx = qx; Qy = qy; Qz = qz; Valid = 1;
        }
    }

    /// <summary>lw_frame: one frame of tracker input (absolute time in seconds, five devices).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Frame
    {
        public double Time;
        public Device Head, LeftHand, RightHand, LeftFoot, RightFoot;
    }

    /// <summary>lw_accent_settings; start from AccentSettings.Default().</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct AccentSettings
    {
        [MarshalAs(UnmanagedType.LPStr)] public string Classes; // comma-separated; null or "" = all
        public int K;                 // matches per hand (1..32)
        public double Exaggeration;   // > 0
        public double UserHeight;     // metres; 0 = the database skeleton's height
        public double HandIk;         // 0..1
        public double SmoothHalflife; // seconds
        public int RecognizeClass;    // 1: several classes allowed -> recognise the activity, search only its class; 0: all
        public double FootLiftHeight; // metres (0..0.5) a released foot is lifted on its way back; 0 = slides (ABI 3)
        public double FootLockSlack;  // metres (0..1) the synthesized foot may move from a plant before it creeps (ABI 4)
        public double FootSwingSpeed; // m/s (0..10) above which a free foot swings clear of the floor; 0 = off (ABI 4)
        public double TravelWeight;   // (0..100) weight of the user's head travel against the hand features; 0 = off (ABI 6)
        public double MaxHeadHeightDiff; // (0..2) an upright user's candidates at most this share of height lower in the head (a lower user's, higher, unless none would be left); 0 = off (ABI 7)
        public double SmoothFeedforward; // (0..1) share of the candidates' own motion the smoothing plays forward; 0 = off, lags (ABI 8)
        public double LyingRootSmoothing; // (1..20) times the root's smoothing half-life for a lying user; 1 = off (ABI 9)
        public double LyingCrown;      // (0..1) share of a lying user's candidate turn from the headset (yaw from its crown, roll from its face; the standing IK body taken out); 0 = off (ABI 10)
        public double OtherClassCost;  // 0, or a factor (1..1e6): while the class is recognised, the other classes are searched too, their distances times it; 0 = the recognised class only (ABI 11)
        public double SearchInterval;  // seconds (0..1) between two searches of the database; in between the matches are continued in their trials; 0 = every frame (ABI 13)
        public int Floor;              // 1: feet never go through the floor (the knee bends; a foot pushed into it stands on it); 0: they may (ABI 14)
        public double FloorHeight;     // metres (-10..10): the play area's floor is y = FloorHeight (ABI 14)
        public double FootLockHoldSeconds;    // seconds (0..10) a planted foot stays put before it creeps; 0 = it creeps from touch-down (ABI 15)

        public static AccentSettings Default()
        {
            AccentSettings s;
            Native.lw_accent_settings_default(out s);
            return s;
        }
    }

    /// <summary>lw_walker_root: how the walker's root travels.</summary>
    public enum WalkerRoot { Smooth = 0, Pivot = 1 }

    /// <summary>lw_walker_settings; start from WalkerSettings.Default().</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct WalkerSettings
    {
        public WalkerRoot Root;        // Smooth: even root, legs hold the planted feet (default); Pivot: document 001
        public double MaxTurnPerStep;  // radians of heading change per step, >= 0
        public double SoftReach;       // smooth root: fraction of a leg's length it may straighten to, (0, 1]
        // The ground walked on (smooth root): the JSON of a path file's "ground" object, e.g.
        // {"slope": {"origin": [0, 1], "direction": [0, 1], "grade": 0.1}}, {"heightfield": {...}} or
        // {"stairs": {...}} (docs/walkcycle.md); null or "" = the flat floor.
        [MarshalAs(UnmanagedType.LPStr)] public string GroundJson;
        public double StairsCadence;   // stairs: the cycle's rate on the flight, a fraction of the flat walk's, (0, 1] (ABI 5)

        public static WalkerSettings Default()
        {
            WalkerSettings s;
            Native.lw_walker_settings_default(out s);
            return s;
        }
    }

    /// <summary>Raw entry points of liblegwork (DllImport name "legwork").</summary>
    public static class Native
    {
        public const string Lib = "legwork";

        [DllImport(Lib)] public static extern uint lw_abi_version();
        [DllImport(Lib)] public static extern IntPtr lw_version_string();
        [DllImport(Lib)] public static extern IntPtr lw_last_error();
        [DllImport(Lib)] public static extern IntPtr lw_status_name(Status s);

        [DllImport(Lib)] public static extern Status lw_database_load([MarshalAs(UnmanagedType.LPStr)] string path, out IntPtr db);
        [DllImport(Lib)] public static extern void lw_database_destroy(IntPtr db);
        [DllImport(Lib)] public static extern int lw_database_class_count(Database db);
        [DllImport(Lib)] public static extern IntPtr lw_database_class_name(Database db, int i);
        [DllImport(Lib)] public static extern int lw_database_window_count(Database db);
        [DllImport(Lib)] public static extern IntPtr lw_database_skeleton(Database db);

        [DllImport(Lib)] public static extern Status lw_skeleton_load_bvh([MarshalAs(UnmanagedType.LPStr)] string path, out IntPtr s);
        [DllImport(Lib)] public static extern void lw_skeleton_destroy(IntPtr s);
        [DllImport(Lib)] public static extern int lw_skeleton_joint_count(Skeleton s);
        [DllImport(Lib)] public static extern IntPtr lw_skeleton_joint_name(Skeleton s, int joint);
        [DllImport(Lib)] public static extern Status lw_skeleton_parents(Skeleton s, [Out] int[] parents, int capacity);

        [DllImport(Lib)] public static extern Status lw_frames_from_bvh([MarshalAs(UnmanagedType.LPStr)] string path, double rate,
                                                                        int dropFirst, out IntPtr frames, out int count);
        [DllImport(Lib)] public static extern void lw_frames_free(IntPtr frames);

        [DllImport(Lib)] public static extern void lw_accent_settings_default(out AccentSettings s);
        [DllImport(Lib)] public static extern Status lw_model_create_accent(Database db, ref AccentSettings s, out IntPtr model);
        [DllImport(Lib)] public static extern Status lw_model_create_ik(Skeleton skeleton, out IntPtr model);
        [DllImport(Lib)] public static extern Status lw_model_create_wip(Skeleton skeleton, out IntPtr model);
        [DllImport(Lib)] public static extern Status lw_model_create_walker([MarshalAs(UnmanagedType.LPStr)] string keysJson, out IntPtr model);
        [DllImport(Lib)] public static extern void lw_walker_settings_default(out WalkerSettings s);
        [DllImport(Lib)] public static extern Status lw_model_create_walker_with_settings([MarshalAs(UnmanagedType.LPStr)] string keysJson,
                                                                                          ref WalkerSettings s, out IntPtr model);
        [DllImport(Lib)] public static extern void lw_model_destroy(IntPtr model);
        [DllImport(Lib)] public static extern Method lw_model_method(Model model);
        [DllImport(Lib)] public static extern IntPtr lw_model_skeleton(Model model);
        [DllImport(Lib)] public static extern IntPtr lw_model_humanoid_name(Model model, int joint, int vrm);

        [DllImport(Lib)] public static extern Status lw_avatar_create(Model model, out IntPtr avatar);
        [DllImport(Lib)] public static extern void lw_avatar_destroy(IntPtr avatar);
        [DllImport(Lib)] public static extern Status lw_avatar_reset(Avatar avatar);
        [DllImport(Lib)] public static extern Status lw_avatar_set_floor(Avatar avatar, double left, double right);
        [DllImport(Lib)] public static extern Status lw_avatar_update(Avatar avatar, ref Frame frame);
        [DllImport(Lib)] public static extern Status lw_avatar_pose(Avatar avatar, [Out] double[] localRotations, [Out] double[] rootPosition,
                                                                    [Out] double[] worldPositions, int capacity);

        [DllImport(Lib)] public static extern int lw_avatar_info_count(Avatar avatar);
        [DllImport(Lib)] public static extern Status lw_avatar_info_field(Avatar avatar, int i, out IntPtr name, out double number, out IntPtr text);
        [DllImport(Lib)] public static extern Status lw_avatar_info_find(Avatar avatar, [MarshalAs(UnmanagedType.LPStr)] string name,
                                                                        out double number, out IntPtr text);
        [DllImport(Lib)] public static extern Status lw_convert_positions(Engine engine, int toEngine, [In, Out] double[] xyz, int count);
        [DllImport(Lib)] public static extern Status lw_convert_rotations(Engine engine, int toEngine, [In, Out] double[] wxyz, int count);

        /// <summary>A C string owned by legwork (never freed here), or null.</summary>
        public static string Str(IntPtr p) { return p == IntPtr.Zero ? null : Marshal.PtrToStringAnsi(p); }

        /// <summary>Throws LegworkException for a negative status; returns the status otherwise.</summary>
        public static Status Check(Status s)
        {
            if (s < 0) throw new LegworkException(s, Str(lw_last_error()) ?? Library.StatusName(s));
            return s;
        }
    }

    /// <summary>Version, status names and the ABI check.</summary>
    public static class Library
    {
        /// <summary>The ABI this file was written for (LW_ABI_VERSION).</summary>
        public const uint AbiVersion = 15;

        public static string Version { get { return Native.Str(Native.lw_version_string()); } }
        public static string StatusName(Status s) { return Native.Str(Native.lw_status_name(s)); }

        /// <summary>Throws when the loaded liblegwork speaks another ABI than this file.</summary>
        public static void CheckAbi()
        {
            uint abi = Native.lw_abi_version();
            if (abi != AbiVersion)
                throw new LegworkException(Status.Unsupported, "liblegwork ABI " + abi + ", Legwork.cs expects " + AbiVersion);
        }
    }

    /// <summary>Base of the owning handles: released once, by Dispose or the finalizer.</summary>
    public abstract class Handle : SafeHandle
    {
        readonly SafeHandle parent; // kept alive (and AddRef'ed) while this handle lives

        protected Handle(IntPtr p, SafeHandle parent) : base(IntPtr.Zero, true)
        {
            SetHandle(p);
            if (parent != null)
            {
                bool added = false;
                parent.DangerousAddRef(ref added);
                if (added) this.parent = parent;
            }
        }

        public override bool IsInvalid { get { return handle == IntPtr.Zero; } }

        protected abstract void Destroy(IntPtr p);

        protected override bool ReleaseHandle()
        {
            Destroy(handle);
            if (parent != null) parent.DangerousRelease();
            return true;
        }
    }

    /// <summary>A skeleton: from a BVH file (owned) or borrowed from a database or model (kept alive).</summary>
    public sealed class Skeleton : Handle
    {
        readonly bool owned;

        Skeleton(IntPtr p, bool owned, SafeHandle owner) : base(p, owner) { this.owned = owned; }

        internal static Skeleton Borrow(IntPtr p, SafeHandle owner) { return new Skeleton(p, false, owner); }

        /// <summary>The skeleton of a BVH file (units detected, metres).</summary>
        public static Skeleton LoadBvh(string path)
        {
            IntPtr p;
            Native.Check(Native.lw_skeleton_load_bvh(path, out p));
            return new Skeleton(p, true, null);
        }

        protected override void Destroy(IntPtr p) { if (owned) Native.lw_skeleton_destroy(p); }

        public int JointCount { get { return Native.lw_skeleton_joint_count(this); } }
        public string JointName(int joint) { return Native.Str(Native.lw_skeleton_joint_name(this, joint)); }

        /// <summary>Parent index per joint (-1 for the root), depth-first order.</summary>
        public int[] Parents()
        {
            int[] p = new int[JointCount];
            Native.Check(Native.lw_skeleton_parents(this, p, p.Length));
            return p;
        }
    }

    /// <summary>An accentuation database, memory-mapped read-only; shareable by many models.</summary>
    public sealed class Database : Handle
    {
        Database(IntPtr p) : base(p, null) { }

        /// <summary>Maps and checks a .lwdb file built by `legwork accent build`.</summary>
        public static Database Load(string path)
        {
            IntPtr p;
            Native.Check(Native.lw_database_load(path, out p));
            return new Database(p);
        }

        protected override void Destroy(IntPtr p) { Native.lw_database_destroy(p); }

        public int ClassCount { get { return Native.lw_database_class_count(this); } }
        public string ClassName(int i) { return Native.Str(Native.lw_database_class_name(this, i)); }
        public int WindowCount { get { return Native.lw_database_window_count(this); } }
        public Skeleton Skeleton { get { return Skeleton.Borrow(Native.lw_database_skeleton(this), this); } }
    }

    /// <summary>An immutable avatar model of one method; shareable by many avatars and threads.</summary>
    public sealed class Model : Handle
    {
        Model(IntPtr p, SafeHandle parent) : base(p, parent) { }

        /// <summary>Accentuation over a database (kept alive by the model).</summary>
        public static Model CreateAccent(Database db, AccentSettings settings)
        {
            IntPtr p;
            Native.Check(Native.lw_model_create_accent(db, ref settings, out p));
            return new Model(p, db);
        }

        /// <summary>The full-body IK avatar (VRIK-style) on a skeleton (copied).</summary>
        public static Model CreateIk(Skeleton skeleton)
        {
            IntPtr p;
            Native.Check(Native.lw_model_create_ik(skeleton, out p));
            return new Model(p, null);
        }

        /// <summary>Walking-in-place legs on a skeleton (copied); call Avatar.SetFloor after creating an avatar.</summary>
        public static Model CreateWip(Skeleton skeleton)
        {
            IntPtr p;
            Native.Check(Native.lw_model_create_wip(skeleton, out p));
            return new Model(p, null);
        }

        /// <summary>A walk-cycle walker from a key-pose JSON file, steered by the head's yaw.</summary>
        public static Model CreateWalker(string keysJsonPath)
        {
            IntPtr p;
            Native.Check(Native.lw_model_create_walker(keysJsonPath, out p));
            return new Model(p, null);
        }

        /// <summary>The walker with settings (root motion, turning, reach, the ground); a bad value
        /// raises LegworkException naming the field.</summary>
        public static Model CreateWalker(string keysJsonPath, WalkerSettings settings)
        {
            IntPtr p;
            Native.Check(Native.lw_model_create_walker_with_settings(keysJsonPath, ref settings, out p));
            return new Model(p, null);
        }

        protected override void Destroy(IntPtr p) { Native.lw_model_destroy(p); }

        public Method Method { get { return Native.lw_model_method(this); } }
        /// <summary>The output pose's skeleton.</summary>
        public Skeleton Skeleton { get { return Skeleton.Borrow(Native.lw_model_skeleton(this), this); } }
        /// <summary>Unity HumanBodyBones name (vrm = false) or VRM humanoid name of a joint, or null.</summary>
        public string HumanoidName(int joint, bool vrm) { return Native.Str(Native.lw_model_humanoid_name(this, joint, vrm ? 1 : 0)); }
    }

    /// <summary>One avatar: its state and output pose. Use from one thread at a time.</summary>
    public sealed class Avatar : Handle
    {
        readonly int joints;

        Avatar(IntPtr p, Model model) : base(p, model) { joints = model.Skeleton.JointCount; }

        /// <summary>A new avatar of `model` (kept alive by the avatar).</summary>
        public static Avatar Create(Model model)
        {
            IntPtr p;
            Native.Check(Native.lw_avatar_create(model, out p));
            return new Avatar(p, model);
        }

        protected override void Destroy(IntPtr p) { Native.lw_avatar_destroy(p); }

        public int JointCount { get { return joints; } }
        public void Reset() { Native.Check(Native.lw_avatar_reset(this)); }
        /// <summary>Walking-in-place only: tracker-space floor heights under each ankle (metres).</summary>
        public void SetFloor(double left, double right) { Native.Check(Native.lw_avatar_set_floor(this, left, right)); }

        /// <summary>One frame; Ok, Degraded, Rejected or Restarted. Allocates nothing.</summary>
        public Status Update(ref Frame frame) { return Native.Check(Native.lw_avatar_update(this, ref frame)); }

        /// <summary>The current pose into caller arrays (any may be null): local rotations (4 per joint,
        /// w x y z), the root's world position (3), world joint positions (3 per joint). Allocates nothing.</summary>
        public void GetPose(double[] localRotations, double[] rootPosition, double[] worldPositions)
        {
            if (localRotations != null && localRotations.Length < 4 * joints)
                throw new ArgumentException("localRotations needs " + 4 * joints + " doubles (4 per joint)", "localRotations");
            if (rootPosition != null && rootPosition.Length < 3)
                throw new ArgumentException("rootPosition needs 3 doubles", "rootPosition");
            if (worldPositions != null && worldPositions.Length < 3 * joints)
                throw new ArgumentException("worldPositions needs " + 3 * joints + " doubles (3 per joint)", "worldPositions");
            Native.Check(Native.lw_avatar_pose(this, localRotations, rootPosition, worldPositions, joints));
        }

        /// <summary>A number of the last consumed frame's figures, by the server's pose "info" names
        /// (e.g. "match_weight", "active_class", "speed"); LegworkException listing the avatar's fields
        /// when there is no such field, or when it is a text (use InfoText). Allocates nothing when found.</summary>
        public double InfoNumber(string name)
        {
            double number;
            IntPtr text;
            Native.Check(Native.lw_avatar_info_find(this, name, out number, out text));
            if (text != IntPtr.Zero)
                throw new LegworkException(Status.InvalidArgument, "info field '" + name + "' is a text ('" + Native.Str(text) + "'): use InfoText");
            return number;
        }

        /// <summary>A text of the last consumed frame's figures (e.g. accentuation's "match": "matched");
        /// null when the field is a number; LegworkException listing the fields when there is none.</summary>
        public string InfoText(string name)
        {
            double number;
            IntPtr text;
            Native.Check(Native.lw_avatar_info_find(this, name, out number, out text));
            return Native.Str(text);
        }

        /// <summary>Every figure of the last consumed frame: name to double or string (allocates).</summary>
        public System.Collections.Generic.Dictionary<string, object> Info
        {
            get
            {
                var all = new System.Collections.Generic.Dictionary<string, object>();
                int n = Native.lw_avatar_info_count(this);
                for (int i = 0; i < n; ++i)
                {
                    IntPtr name, text;
                    double number;
                    Native.Check(Native.lw_avatar_info_field(this, i, out name, out number, out text));
                    all[Native.Str(name)] = text != IntPtr.Zero ? (object)Native.Str(text) : number;
                }
                return all;
            }
        }
    }

    /// <summary>Tracker frames from files.</summary>
    public static class Tracker
    {
        /// <summary>Frames from a BVH trial's head, wrists and ankles at `rate` Hz (0 = the file's rate),
        /// the CMU T-pose frame 0 dropped if dropFirst.</summary>
        public static Frame[] FramesFromBvh(string path, double rate, bool dropFirst)
        {
            IntPtr p;
            int count;
            Native.Check(Native.lw_frames_from_bvh(path, rate, dropFirst ? 1 : 0, out p, out count));
            try
            {
                Frame[] frames = new Frame[count];
                int size = Marshal.SizeOf(typeof(Frame));
                for (int i = 0; i < count; ++i)
                    frames[i] = (Frame)Marshal.PtrToStructure(new IntPtr(p.ToInt64() + (long)i * size), typeof(Frame));
                return frames;
            }
            finally
            {
                Native.lw_frames_free(p);
            }
        }
    }

    /// <summary>Engine frames (formulas in legwork/core/engine.hpp and the README).</summary>
    public static class Convert
    {
        /// <summary>In place: positions (xyz, count = length / 3) to the engine's frame (toEngine) or back.</summary>
        public static void Positions(Engine engine, bool toEngine, double[] xyz)
        {
            Native.Check(Native.lw_convert_positions(engine, toEngine ? 1 : 0, xyz, xyz.Length / 3));
        }

        /// <summary>In place: rotations (w x y z, count = length / 4) to the engine's frame (toEngine) or back.</summary>
        public static void Rotations(Engine engine, bool toEngine, double[] wxyz)
        {
            Native.Check(Native.lw_convert_rotations(engine, toEngine ? 1 : 0, wxyz, wxyz.Length / 4));
        }
    }
}
