"""A walk sampled from a gait prior and seen through a camera, and a clip tracked from its
masks, with `import jgpm`.

    PYTHONPATH=build/python python3 tracker/python/example.py MODEL.json CAMERA.yaml OUT.csv [CLIP]

For a JGPM-family model (jgpm, ml-jgpm-torus, ml-jgpm-cyl) the walk goes round the gait
manifold (phase 0 -> 1, twice); for the others it follows the training latent points. Each
row of OUT.csv is a frame's joints in the camera's image (pixels; empty when behind it).
With CLIP (a `jgpm render` folder), its observed masks are tracked, as any segmenter's
would be, and the root's error against the clip's ground truth printed."""
import csv
import sys

import numpy as np

import jgpm


def walk(model, frames=60):
    """Latent points of two gait cycles."""
    if model.has_manifold:
        phases = np.linspace(0, 2, frames, endpoint=False) % 1
        return np.array([model.manifold_to_latent(p, 0.0, 1.0) for p in phases])
    return model.latent[:frames]


def main(model_path, camera_path, out_path):
    model = jgpm.load_model(model_path)
    camera = jgpm.Camera.from_yaml(camera_path)
    poses = model.mean_pose(walk(model))  # frames x channels, degrees
    joints = model.joint_positions(poses)  # frames x joints x 3, mm, the pelvis over the origin
    pixels = camera.project(joints.reshape(-1, 3)).reshape(len(joints), -1, 2)
    with open(out_path, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["frame"] + [f"joint{j}_{axis}" for j in range(joints.shape[1]) for axis in "uv"])
        for k, frame in enumerate(pixels):
            out.writerow([k] + ["" if np.isnan(v) else f"{v:.2f}" for v in frame.ravel()])
    print(f"{model.kind}: {len(poses)} frames of {joints.shape[1]} joints seen by {camera.name} -> {out_path}")


def track(model_path, clip):
    """The clip's observed masks through the tracker; the root's mean error, mm."""
    import json
    from pathlib import Path

    import cv2
    clip = Path(clip)
    names = sorted(p.stem for p in clip.glob("cam*.yaml"))
    tracker = jgpm.Tracker(jgpm.load_model(model_path), [jgpm.Camera.from_yaml(str(clip / f"{n}.yaml")) for n in names])
    truth = json.loads((clip / "ground_truth.json").read_text())["frames"]
    estimates = []
    for k in range(len(truth)):
        masks = [cv2.imread(str(clip / "observed" / n / f"{k:06d}.png"), cv2.IMREAD_GRAYSCALE) for n in names]
        estimates += tracker.step(masks)
    estimates += tracker.finish()
    errors = [np.linalg.norm(e["root_mm"] - np.array(truth[e["frame"]]["joints_mm"][0]))
              for e in estimates if e["joints_mm"] is not None]
    print(f"{clip.name}: {len(errors)} of {len(estimates)} frames tracked, root {np.mean(errors):.1f} mm off")


if __name__ == "__main__":
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    main(*sys.argv[1:4])
    if len(sys.argv) == 5:
        track(sys.argv[1], sys.argv[4])
