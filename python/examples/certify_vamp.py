"""Certify (and repair) a path from VAMP with viaroad.

    python certify_vamp.py ROBOT_DIR SCENE.yaml REQUEST.yaml [PATH_FILE]

ROBOT_DIR holds the robot's .urdf and .srdf (e.g. scenes/arms/panda); SCENE and REQUEST are a
MotionBenchMaker problem (a MoveIt PlanningScene and MotionPlanRequest). When the `vamp` package
is importable and no PATH_FILE is given, VAMP plans the request first (RRT-Connect on its sphere
model); otherwise the path is read from PATH_FILE (one configuration per line, the group's joint
order). viaroad then proves each straight joint-space segment free or finds where it collides
with the robot's real meshes, and repairs the path.
"""

import sys

import numpy as np

import viaroad


def plan_with_vamp(scene):
    """A path from VAMP's RRT-Connect for the scene's query, or None without `vamp`."""
    try:
        import vamp  # noqa: F401
    except ImportError:
        return None
    # VAMP needs its own environment (spheres, boxes); building it from a MoveIt scene is
    # VAMP's `problem_tar_to_pkl_json.py`'s job. Here the start and goal are planned in an
    # empty environment, a path VAMP's checks accept and viaroad then checks for real.
    start, goal = scene.queries()[0]
    robot, planner, settings, sampler = vamp.configure_robot_and_planner_with_kwargs(
        "panda", "rrtc"
    )
    result = planner(start, goal, vamp.Environment(), settings, sampler)
    simple = robot.simplify(result.path, vamp.Environment(), vamp.SimplifySettings(), sampler)
    return np.array(simple.path.numpy())


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    robot_dir, scene_file, request_file = sys.argv[1:4]
    scene = viaroad.Scene.load_moveit(robot_dir, scene_file, request_file)
    path = None if len(sys.argv) > 4 else plan_with_vamp(scene)
    if path is None:
        if len(sys.argv) < 5:
            sys.exit("vamp is not importable: give a PATH_FILE")
        path = np.loadtxt(sys.argv[4], ndmin=2)
    cert = scene.certify(path)
    print(f"{len(path)} waypoints: {cert['status']} ({cert['seconds'] * 1e3:.2f} ms)")
    for i, seg in enumerate(cert["segments"]):
        if seg["verdict"] == "collides":
            pairs = ", ".join(f"{a} ~ {b}" for a, b in seg["pairs"])
            print(f"  segment {i + 1}: collides in {seg['intervals']}: {pairs}")
        elif seg["verdict"] == "undecided":
            print(f"  segment {i + 1}: undecided: {seg['reason']}")
    if cert["status"] != "free":
        fixed, report = scene.repair(path, time=10.0)
        print(
            f"repaired: {'certified free' if report['certified'] else 'not certified'}; "
            f"length {report['length_before']:.3f} -> {report['length_after']:.3f}, "
            f"{report['seconds'] * 1e3:.1f} ms"
        )
        np.savetxt("fixed.path", fixed)
        print("fixed path written to fixed.path")


if __name__ == "__main__":
    main()
