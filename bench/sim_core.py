"""Real-time factor of the simulation core, headless, on the seed robot (run by hand).

    python bench/sim_core.py [--seconds 20] [--camera-seconds 3]

Cases: physics + diff drive (in-process, every step) + joint/base reads; + the lidar at 12 Hz;
+ the seed's 800x800 camera at 30 Hz rendered in the same loop with TinyRenderer; the same with
the EGL renderer plugin. The simulator server no longer renders (the camera has its own process,
measured end to end by bench/bringup.py); the camera cases show what one process doing both costs.
Target (issue 5): >= 20x with the lidar. Prints one line per case and the machine and date.

``--frames N`` instead times what one camera frame costs, step by step (median of N frames, ms,
TinyRenderer then EGL): mirroring the state (base pose and joints), the view matrix, PyBullet's
render, packing RGBA into rgb8 (and the way it was packed before, for comparison), building the
Image, serializing it and Zenoh's put (no remote subscriber).
"""

from __future__ import annotations

import argparse
import os
import platform
import time
from collections.abc import Iterator
from contextlib import contextmanager
from datetime import datetime, timezone
from pathlib import Path

from launchkit.stock.gazebo_ros.sim.diff_drive import DiffDriveController
from launchkit.stock.gazebo_ros.sim.engine import Simulation
from launchkit.stock.gazebo_ros.sim.plugins import load_plugins
from launchkit.stock.gazebo_ros.sim.quiet import silence_c_stdout
from launchkit.stock.gazebo_ros.sim.sensors import Camera, RateGate
from launchkit.stock.gazebo_ros.sim.world import load_world, resolve_world

SEED = Path(__file__).resolve().parents[1] / "urdf" / "three_wheeled_robot.urdf"


def run(seconds: float, lidar: bool, camera: bool, egl: bool = False) -> float:
    """Sim seconds per wall second for one case."""
    sim = Simulation(load_world(resolve_world("obstacles")), egl=egl)
    try:
        entity = sim.spawn("robot", SEED.read_text(), (0, 0, 0.151, 0, 0, 0))
        plugins = load_plugins(sim, entity, lambda _m: None)
        _, params = plugins.diff_drives[0]
        renderer = Camera(sim, entity, plugins.cameras[0][1])
        camera_gate = RateGate(renderer.config.update_rate)
        sim.step(240)
        ctl = DiffDriveController(params, start_time=sim.time)
        ctl.set_command(0.3, 0.4)  # a circle: stays clear of the obstacles
        steps = round(seconds / sim.time_step)
        start = time.perf_counter()
        for _ in range(steps):
            joints = sim.joint_states(entity)
            wheels = (joints[params.left_joint][1], joints[params.right_joint][1])
            update = ctl.update(sim.time, wheels, sim.base_state(entity))
            if update is not None:
                sim.set_joint_velocities(entity, update.command.velocities, 8.0)
            if lidar:
                plugins.poll_lidars(sim.time)
            if camera and camera_gate.due(sim.time):
                renderer.render()
            sim.step()
        return seconds / (time.perf_counter() - start)
    finally:
        sim.close()


def frame_costs(frames: int, egl: bool) -> dict[str, float]:
    """Median milliseconds of each step of a camera frame (see the module's docstring)."""
    import statistics

    import numpy as np
    import zenoh

    from launchkit.ros.msgs import codec
    from launchkit.stock.gazebo_ros import messages

    sim = Simulation(load_world(resolve_world("obstacles")), egl=egl)
    session = zenoh.open(zenoh.Config())
    try:
        entity = sim.spawn("robot", SEED.read_text(), (0, 0, 0.151, 0, 0, 0))
        camera = Camera(sim, entity, load_plugins(sim, entity, lambda _m: None).cameras[0][1])
        c = camera.config
        publisher = session.declare_publisher("bench/camera")
        coder = codec("sensor_msgs/msg/Image")
        steps: dict[str, list[float]] = {}

        @contextmanager
        def timed(step: str) -> Iterator[None]:
            start = time.perf_counter()
            yield
            steps.setdefault(step, []).append((time.perf_counter() - start) * 1000)

        for i in range(frames):
            joints = {j: 0.1 * i for j in entity.joints}
            with timed("mirror state"):
                sim.set_state(entity, (0.01 * i, 0.0, 0.151), (0.0, 0.0, 0.0, 1.0), joints)
            with timed("view matrix"):
                matrix = camera.view_matrix()
            with timed("render (getCameraImage)"):
                rgba = camera.render_rgba(matrix)
            with timed("pack rgb8"):
                frame = camera.pack(rgba)
            with timed("  before: (N,3) view .tobytes()"):
                np.asarray(rgba, dtype=np.uint8).reshape(-1, 4)[:, :3].tobytes()
            with timed("build Image"):
                msg = messages.image(c, 1.0, frame)
            with timed("serialize"):
                data = coder.serialize(msg)
            with timed("put"):
                publisher.put(data)
        return {step: statistics.median(values) for step, values in steps.items()}
    finally:
        session.close()  # type: ignore[no-untyped-call]
        sim.close()


def main() -> None:
    """Run every case and print the results."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0, help="sim seconds without camera")
    parser.add_argument("--camera-seconds", type=float, default=3.0, help="sim seconds with it")
    parser.add_argument("--frames", type=int, default=0, help="time each step of N frames")
    args = parser.parse_args()
    silence_c_stdout()  # the EGL plugin prints a line per frame
    if args.frames:
        for egl in (False, True):
            costs = frame_costs(args.frames, egl)
            for step, ms in costs.items():
                print(f"{'EGL' if egl else 'TinyRenderer':12s} {step:34s} {ms:8.2f} ms")
            total = sum(v for k, v in costs.items() if not k.startswith(" "))
            print(f"{'EGL' if egl else 'TinyRenderer':12s} {'total':34s} {total:8.2f} ms")
        return
    cases = [
        ("physics + diff drive", args.seconds, False, False, False),
        ("+ lidar 360 rays 12 Hz", args.seconds, True, False, False),
        ("+ camera 800x800 30 Hz TinyRenderer", args.camera_seconds, True, True, False),
        ("+ camera 800x800 30 Hz EGL", args.camera_seconds, True, True, True),
    ]
    print(
        f"# {platform.node()} {platform.processor() or platform.machine()}, {os.cpu_count()} "
        f"CPUs, Python {platform.python_version()}, {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC"
    )
    for label, seconds, lidar, camera, egl in cases:
        rtf = run(seconds, lidar, camera, egl)
        print(f"{label:40s} real-time factor {rtf:7.2f}x ({seconds:g} sim s)", flush=True)


if __name__ == "__main__":
    main()
