#!/usr/bin/env python3
"""Scores a `jgpm track --people all` run on a real video that has no annotations against
OpenCV's HOG people detector, an independent cue (image gradients, not background
subtraction). A proxy, not truth: HOG misses people under about 64 px (the video is
upscaled 2x first, so about 32 px), people cut by the image's edge and some in groups,
and fires on a few static things; figures compare runs of one video, they are not MOT
scores.

  score_against_hog.py VIDEO RUN_DIR CAMERA.yaml [--step 2] [--draw OUT.png --frames 100,200]

Every --step-th frame: HOG boxes (NMS 0.3, score over 0.3; boxes at one place in more than
15% of the frames, static, and boxes holding another are dropped) matched greedily at IoU
0.3 to the tracked people's boxes (their joints projected through CAMERA.yaml, grown to
HOG's margins: 8% of the height above the head, 12% each side, the whole 4:3 taller).
Prints the share of HOG boxes matched (a recall) and of tracked people on a HOG box (a
precision). HOG's boxes are cached beside the run (hog_STEP.json).

Walkers: the kept HOG boxes linked from one scored frame to the next (IoU 0.3, across one
missed frame at most) are HOG's walkers; those followed for --walker-s (default 2, the issue's
"in view for 2 s") are counted as tracked when a tracked person is on half or more of their
boxes, and the delay from their first box to the first one a tracked person is on is
reported (birth latency). Missed walkers are listed with their frames and place."""
import argparse
import json
import os

import cv2
import numpy as np


def hog_boxes(video, step):
    hog = cv2.HOGDescriptor()
    hog.setSVMDetector(cv2.HOGDescriptor_getDefaultPeopleDetector())
    capture, index, found = cv2.VideoCapture(video), 0, {}
    while True:
        ok, image = capture.read()
        if not ok:
            break
        if index % step == 0:
            big = cv2.resize(image, None, fx=2, fy=2)
            boxes, weights = hog.detectMultiScale(big, winStride=(8, 8), padding=(8, 8), scale=1.05)
            weights = np.array(weights).reshape(-1)
            keep = cv2.dnn.NMSBoxes([list(map(int, b)) for b in boxes], [float(w) for w in weights], 0.5, 0.3) \
                if len(boxes) else []
            found[index] = [[float(v) / 2 for v in boxes[k]] + [float(weights[k])] for k in np.array(keep).reshape(-1)]
        index += 1
    if not found:
        raise SystemExit(f"{video}: no frames could be read")
    return found


def iou(a, b):
    x0, y0 = max(a[0], b[0]), max(a[1], b[1])
    x1, y1 = min(a[0] + a[2], b[0] + b[2]), min(a[1] + a[3], b[1] + b[3])
    inter = max(0, x1 - x0) * max(0, y1 - y0)
    return inter / (a[2] * a[3] + b[2] * b[3] - inter)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("video")
    parser.add_argument("run", help="the --out folder of jgpm track --people all")
    parser.add_argument("camera", help="the camera YAML the run used")
    parser.add_argument("--step", type=int, default=2)
    parser.add_argument("--draw", help="PNG of --frames: HOG red, tracked green with ids")
    parser.add_argument("--frames", default="")
    parser.add_argument("--walker-s", type=float, default=2, help="walkers followed this long are counted")
    args = parser.parse_args()

    cache = os.path.join(args.run, f"hog_{args.step}.json")
    if os.path.exists(cache):
        hog = {int(k): v for k, v in json.load(open(cache)).items()}
    else:
        hog = hog_boxes(args.video, args.step)
        json.dump(hog, open(cache, "w"))
    poses = json.load(open(os.path.join(args.run, "poses.json")))
    if "people" not in poses["frames"][0]:
        raise SystemExit(f"{args.run}/poses.json: not a --people all run (frames have no 'people')")
    camera = cv2.FileStorage(args.camera, cv2.FILE_STORAGE_READ)
    if not camera.isOpened():
        raise SystemExit(f"{args.camera}: cannot read the camera")
    K = camera.getNode("camera_matrix").mat()
    R = camera.getNode("cam_from_world_rotation").mat()
    t = camera.getNode("cam_from_world_translation_mm").mat().reshape(3)

    every = [b for boxes in hog.values() for b in boxes]
    static = lambda b: sum(1 for c in every if iou(b, c) > 0.6) > 0.15 * len(hog)
    holds = lambda a, b: (b[0] >= a[0] - 4 and b[1] >= a[1] - 4 and b[0] + b[2] <= a[0] + a[2] + 4 and
                          b[1] + b[3] <= a[1] + a[3] + 4)

    def hog_kept(frame):
        boxes = [b for b in hog[frame] if b[4] > 0.3 and not static(b)]
        return [b for b in boxes if not any(holds(b, c) for c in boxes if c is not b)]

    def tracked(frame):
        out = []
        for p in frames.get(frame, {}).get("people", []):
            if not p.get("joints_mm"):
                continue
            c = R @ np.array(p["joints_mm"]).T + t[:, None]
            uv = (K @ c)[:2] / c[2]
            x0, y0, x1, y1 = uv[0].min(), uv[1].min(), uv[0].max(), uv[1].max()
            tall = y1 - y0
            x0, x1, y0 = x0 - 0.12 * tall, x1 + 0.12 * tall, y0 - 0.08 * tall
            h = (y1 - y0) / 0.75
            cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
            out.append(([cx - h / 4, cy - h / 2, h / 2, h], p["id"]))
        return out

    frames = {f["frame"]: f for f in poses["frames"]}
    seen = people = matched = 0
    walkers, open_walkers = [], []  # each a list of (frame, box, on a tracked person)
    for frame in sorted(hog):
        boxes, ours = hog_kept(frame), tracked(frame)
        on = [False] * len(boxes)
        cost = np.array([[1 - iou(b, o[0]) for o in ours] for b in boxes]).reshape(len(boxes), len(ours))
        while cost.size and cost.min() <= 0.7:
            i, j = np.unravel_index(np.argmin(cost), cost.shape)
            matched += 1
            on[i] = True
            cost[i, :] = cost[:, j] = 2
        seen, people = seen + len(boxes), people + len(ours)
        # HOG's walkers: each box continues the open walker whose last box it overlaps most.
        open_walkers = [w for w in open_walkers if frame - w[-1][0] <= 2 * args.step]
        link = np.array([[1 - iou(b, w[-1][1]) for w in open_walkers] for b in boxes]).reshape(
            len(boxes), len(open_walkers))
        taken = set()
        while link.size and link.min() <= 0.7:
            i, j = np.unravel_index(np.argmin(link), link.shape)
            open_walkers[j].append((frame, boxes[i], on[i]))
            taken.add(i)
            link[i, :] = link[:, j] = 2
        for i, b in enumerate(boxes):
            if i not in taken:
                walkers.append([(frame, b, on[i])])
                open_walkers.append(walkers[-1])
    print(f"{args.run}: {len(hog)} frames, HOG boxes {seen}, tracked people {people}, matched {matched}: "
          f"HOG boxes matched {matched / max(seen, 1):.3f}, tracked people on a HOG box {matched / max(people, 1):.3f}")
    fps = poses.get("fps") or 0
    if not fps and len(poses["frames"]) > 1:
        f0, f1 = poses["frames"][0], poses["frames"][-1]
        fps = (f1["frame"] - f0["frame"]) / max(f1.get("time_s", 0) - f0.get("time_s", 0), 1e-9)
    long_walkers = [w for w in walkers if (w[-1][0] - w[0][0]) >= args.walker_s * fps]
    followed = [w for w in long_walkers if 2 * sum(on for _, _, on in w) >= len(w)]
    delays = [next(f for f, _, on in w if on) - w[0][0] for w in long_walkers if any(on for _, _, on in w)]
    print(f"HOG walkers in view {args.walker_s:g} s or more: {len(long_walkers)}, tracked on half their boxes or more: "
          f"{len(followed)} ({len(followed) / max(len(long_walkers), 1):.3f}); frames from HOG's first box to the "
          f"first tracked one: median {np.median(delays) if delays else float('nan'):.0f}, "
          f"max {max(delays) if delays else float('nan')}")
    for w in long_walkers:
        if w not in followed:
            b = w[0][1]
            print(f"  missed: frames {w[0][0]}-{w[-1][0]}, {sum(on for _, _, on in w)}/{len(w)} boxes tracked, "
                  f"first box at ({b[0]:.0f}, {b[1]:.0f}) {b[2]:.0f}x{b[3]:.0f} px")

    if args.draw:
        want = {int(f) for f in args.frames.split(",") if f}
        capture, index, images = cv2.VideoCapture(args.video), 0, []
        while want:
            ok, image = capture.read()
            if not ok:
                break
            if index in want:
                for b in hog_kept(index) if index in hog else []:
                    cv2.rectangle(image, (int(b[0]), int(b[1])), (int(b[0] + b[2]), int(b[1] + b[3])), (0, 0, 255), 2)
                for b, pid in tracked(index):
                    cv2.rectangle(image, (int(b[0]), int(b[1])), (int(b[0] + b[2]), int(b[1] + b[3])), (0, 255, 0), 1)
                    cv2.putText(image, str(pid), (int(b[0]), int(b[1])), 0, 0.5, (0, 255, 0), 1)
                cv2.putText(image, str(index), (10, 30), 0, 1, (0, 255, 255), 2)
                images.append(image)
            index += 1
        if images:
            if len(images) % 2:
                images.append(np.zeros_like(images[0]))
            cv2.imwrite(args.draw, np.vstack([np.hstack(images[k:k + 2]) for k in range(0, len(images), 2)]))
            print(f"wrote {args.draw}")


if __name__ == "__main__":
    main()
