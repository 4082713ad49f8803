"""A walk sampled from a gait prior and seen through a camera, with `import jgpm`.

    PYTHONPATH=build/python python3 tracker/python/example.py MODEL.json CAMERA.yaml OUT.csv

For a JGPM-family model (jgpm, ml-jgpm-torus, ml-jgpm-cyl) the walk goes round the gait
manifold (phase 0 -> 1, twice); for the others it follows the training latent points. Each
row of OUT.csv is a frame's joints in the camera's image (pixels; empty when behind it)."""
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


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
