import legwork
from legwork import accent, core

db = accent.build_database("data/cmu", exclude=["bvh/walking/07_02.bvh"])  # or accent.load_database("all.lwdb")
walk = core.resample(legwork.io.read_bvh("data/cmu/bvh/walking/07_02.bvh", drop_first=True), db.fps)
settings = accent.Settings()
settings.user_height = 1.7                                   # metres
model = accent.make_model(db, settings)                      # immutable, shared by avatars
state, pose = accent.State(model), core.Pose(model.skeleton())
for frame in core.tracker_frames_from_motion(walk):          # or core.TrackerFrame(t).set(Device.Head, ...)
    status = accent.update(model, frame, state, pose)        # pose.rotations: (joints, 4) w,x,y,z
print(status, pose.positions(model.skeleton())[model.skeleton().roles["left_ankle"]])  # metres
