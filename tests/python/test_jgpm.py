"""`import jgpm` against independent answers: a PCA model's own basis, finite differences,
OpenCV's projectPoints, the motion's root translation in its file's units, the jgpm
command's own reading of the same files and its tracking of the same masks; and bad input
refused with the file or argument named. Run by ctest (tests/CMakeLists.txt) with PYTHONPATH at the built module, JGPM_BINARY
at the jgpm command and JGPM_DATA (or ../shared/data/cmu) at the CMU trials."""
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

import jgpm

SOURCE = Path(__file__).resolve().parents[2]
BINARY = os.environ.get("JGPM_BINARY", "jgpm")


def cmu_root():
    for root in (os.environ.get("JGPM_DATA"), SOURCE / "data" / "cmu", SOURCE.parent / "shared" / "data" / "cmu"):
        if root and (Path(root) / "subjects").is_dir():
            return Path(root)
    raise unittest.SkipTest("no CMU data (set JGPM_DATA)")


def run_jgpm(*arguments):
    return subprocess.run([BINARY, *map(str, arguments)], capture_output=True, text=True, check=True).stdout


_SHARED = {}  # one temporary folder and one set of trained models for the whole module


def tearDownModule():
    if "temp" in _SHARED:
        _SHARED["temp"].cleanup()


class Fixture(unittest.TestCase):
    """The CMU data, a temporary folder and a PCA, a GPDM and a JGPM model trained by the command
    (GPs for 3 iterations: seconds, not a good prior)."""

    @classmethod
    def setUpClass(cls):
        if "temp" not in _SHARED:
            _SHARED["temp"] = tempfile.TemporaryDirectory()
            folder, data = Path(_SHARED["temp"].name), cmu_root()
            models = {}
            for kind, extra in (("pca", []), ("gpdm", ["--max-iterations", "3"]), ("jgpm", ["--max-iterations", "3"])):
                models[kind] = folder / f"{kind}.json"
                run_jgpm("train", "--model", kind, *extra, "--data", data, "--out", models[kind])
            _SHARED.update(dir=folder, data=data, models=models)
        cls.dir, cls.data, cls.models = _SHARED["dir"], _SHARED["data"], _SHARED["models"]
        cls.amc = cls.data / "subjects" / "07" / "07_01.amc"
        cls.asf = cls.data / "subjects" / "07" / "07.asf"


class ModuleTest(unittest.TestCase):
    def test_version_is_the_commands(self):
        self.assertEqual(run_jgpm("--version").split()[-1], jgpm.__version__)

    def test_docstrings_show_in_help(self):
        self.assertIn("(M, 3) -> (M, D)", jgpm.Model.mean_pose.__doc__)
        self.assertIn("NaN", jgpm.Camera.project.__doc__)


class MotionTest(Fixture):
    def test_an_amc_has_the_commands_frames_and_its_root_where_the_file_puts_it(self):
        motion = jgpm.read_motion(self.amc)
        info = run_jgpm("data", "info", self.amc)
        frames = int(re.search(r"frames (\d+)", info).group(1))
        self.assertEqual(len(motion.joint_names), int(re.search(r"joints (\d+)", info).group(1)))
        self.assertEqual(motion.num_frames, frames)
        self.assertEqual(motion.frames_per_second, 120)
        joints = motion.joint_positions()
        self.assertEqual(joints.shape, (frames, len(motion.joint_names), 3))
        self.assertEqual(motion.joint_names[0], "root")
        # The root's translation is in the ASF's length unit: 1/0.45 inch (CMU's ":length 0.45").
        np.testing.assert_allclose(joints[:, 0, :], motion.values[:, :3] * 25.4 / 0.45, rtol=1e-9, atol=1e-9)
        # A person: the head above the feet by 1.4-2 m in the first frame.
        head = motion.joint_names.index("head")
        foot = motion.joint_names.index("ltoes")
        self.assertTrue(1400 < joints[0, head, 1] - joints[0, foot, 1] < 2000)

    def test_values_are_a_read_only_view(self):
        motion = jgpm.read_motion(self.amc)
        values = motion.values
        self.assertFalse(values.flags.writeable)
        self.assertIsNotNone(values.base)  # a view of the motion's frames, not a copy
        with self.assertRaises(ValueError):
            values[0, 0] = 1

    def test_written_files_read_back_to_the_same_joints(self):
        motion = jgpm.read_motion(self.amc)
        amc, bvh = self.dir / "again.amc", self.dir / "again.bvh"
        motion.write_amc(amc)
        motion.write_bvh(bvh)
        again = jgpm.read_motion(amc, asf=self.asf)
        np.testing.assert_allclose(again.values, motion.values, atol=1e-6)
        # The BVH, read as its own hierarchy (End Sites at the bones' ends) and as the ASF's.
        as_bvh = jgpm.read_motion(bvh)
        as_acclaim = jgpm.read_motion(bvh, asf=self.asf)
        np.testing.assert_allclose(as_acclaim.joint_positions(), motion.joint_positions(), atol=1e-3)
        # Through the BVH's own kinematics: a bone without children ends in an End Site at its end.
        bvh_joints, acclaim_joints = as_bvh.joint_positions(), motion.joint_positions()
        ends = [name for name in as_bvh.joint_names if name.endswith("_end")]
        self.assertGreaterEqual(len(ends), 5)  # head, hands' fingers and thumbs, toes
        for name in ends:
            np.testing.assert_allclose(bvh_joints[:, as_bvh.joint_names.index(name)],
                                       acclaim_joints[:, motion.joint_names.index(name[:-4])], atol=1e-3, err_msg=name)

    def test_a_malformed_file_names_itself_and_its_line(self):
        bad = self.dir / "bad.amc"
        text = self.amc.read_text().splitlines()
        text[12] = "root 1 2 x 4 5 6"
        bad.write_text("\n".join(text) + "\n")
        with self.assertRaises(jgpm.InputError) as caught:
            jgpm.read_motion(bad, asf=self.asf)
        self.assertRegex(str(caught.exception), re.escape(str(bad)) + r":\d+")
        self.assertIsInstance(caught.exception, ValueError)
        with self.assertRaises(jgpm.InputError) as caught:
            jgpm.read_motion(self.dir / "missing.amc", asf=self.asf)
        self.assertIn("missing.amc", str(caught.exception))
        with self.assertRaises(jgpm.InputError):
            jgpm.read_motion(self.dir / "motion.txt")
        plain = self.dir / "plain.bvh"
        jgpm.read_motion(self.amc).write_bvh(plain)
        with self.assertRaises(jgpm.InputError) as caught:
            jgpm.read_motion(plain).write_amc(self.dir / "x.amc")  # a BVH read without asf=
        self.assertIn("no Acclaim skeleton", str(caught.exception))


class ModelTest(Fixture):
    def test_a_pca_models_mean_poses_are_its_basis_times_the_latent_point(self):
        model = jgpm.load_model(self.models["pca"])
        self.assertEqual(model.kind, "pca")
        saved = json.loads(Path(self.models["pca"]).read_text())["model"]
        mean, scale, basis = (np.array(saved[k]) for k in ("channel_mean", "channel_scale", "pca_basis"))
        xs = np.random.default_rng(1).normal(size=(50, 3))
        expected = mean + scale * (xs @ basis.T)
        poses = model.mean_pose(xs)
        self.assertEqual(poses.shape, (50, model.num_channels))
        np.testing.assert_allclose(poses, expected, atol=1e-9)
        np.testing.assert_allclose(model.mean_pose(xs[3]), expected[3], atol=1e-9)  # one point
        np.testing.assert_allclose(model.latent, np.array(saved["latent"]))

    def test_log_density_gradients_match_finite_differences(self):
        for kind in ("pca", "gpdm", "jgpm"):
            model = jgpm.load_model(self.models[kind])
            xs = model.latent[::97] + 0.05
            values, gradients = model.log_density(xs, gradient=True)
            np.testing.assert_allclose(values, model.log_density(xs))
            h = 1e-6
            for d in range(3):
                step = np.zeros(3)
                step[d] = h
                numeric = (model.log_density(xs + step) - model.log_density(xs - step)) / (2 * h)
                np.testing.assert_allclose(gradients[:, d], numeric, rtol=1e-4, atol=1e-4, err_msg=f"{kind}, dim {d}")

    def test_batches_are_the_single_points(self):
        model = jgpm.load_model(self.models["gpdm"])
        xs = model.latent[:7] * 1.1
        for i in range(7):
            np.testing.assert_allclose(model.mean_pose(xs)[i], model.mean_pose(xs[i]), atol=1e-12)
            np.testing.assert_allclose(model.next_latent(xs)[i], model.next_latent(xs[i]), atol=1e-12)
            self.assertAlmostEqual(model.log_density(xs)[i], model.log_density(xs[i]), places=12)
        self.assertTrue(model.has_dynamics)
        # Along the dynamics the next point of a training point is near the training next.
        step = np.linalg.norm(model.latent[1] - model.latent[0])
        self.assertLess(np.linalg.norm(model.next_latent(model.latent[0]) - model.latent[1]), 3 * step + 1e-9)
        pca = jgpm.load_model(self.models["pca"])
        np.testing.assert_allclose(pca.next_latent(xs), xs)  # no dynamics: the point itself

    def test_joint_positions_of_a_mean_pose_stand_like_a_person(self):
        model = jgpm.load_model(self.models["pca"])
        poses = model.mean_pose(model.latent[:4])
        joints = model.joint_positions(poses)
        self.assertEqual(joints.shape[0], 4)
        self.assertEqual(joints.shape[2], 3)
        np.testing.assert_allclose(model.joint_positions(poses[2]), joints[2])
        height = joints[:, :, 1].max(axis=1) - joints[:, :, 1].min(axis=1)
        self.assertTrue(np.all((height > 1300) & (height < 2000)), height)

    def test_the_manifold_round_trips_in_the_jgpm_family_only(self):
        model = jgpm.load_model(self.models["jgpm"])
        self.assertTrue(model.has_manifold)
        for phase in (0.1, 0.45, 0.8):
            x = model.manifold_to_latent(phase, 0.0, 1.0)
            back = model.latent_to_manifold(x)
            self.assertAlmostEqual(back[0], phase, places=3)
        with self.assertRaises(jgpm.InputError) as caught:
            jgpm.load_model(self.models["pca"]).manifold_to_latent(0.1, 0, 1)
        self.assertIn("no gait manifold", str(caught.exception))

    def test_bad_arrays_and_files_are_refused_by_name(self):
        model = jgpm.load_model(self.models["pca"])
        with self.assertRaises(TypeError) as caught:
            model.mean_pose(np.zeros((5, 2)))
        self.assertIn("latent: expected an array of shape (M, 3)", str(caught.exception))
        self.assertIn("got (5 x 2)", str(caught.exception))
        with self.assertRaises(ValueError) as caught:
            model.mean_pose([[0.0, float("nan"), 0.0]])
        self.assertIn("NaN", str(caught.exception))
        with self.assertRaises(TypeError):
            model.mean_pose([["a", "b", "c"]])
        np.testing.assert_allclose(model.mean_pose(np.zeros((2, 3), np.float32)), model.mean_pose(np.zeros((2, 3))))
        not_a_model = self.dir / "not_a_model.json"
        not_a_model.write_text('{"format": "something else"}')
        with self.assertRaises(jgpm.InputError) as caught:
            jgpm.load_model(not_a_model)
        self.assertIn("not_a_model.json", str(caught.exception))


class TrainInferTest(Fixture):
    def test_training_is_the_commands_and_reports_its_progress(self):
        reports = []
        model = jgpm.train("gpdm", data=str(self.data), max_iterations=3, progress=reports.append)
        command = jgpm.load_model(self.models["gpdm"])  # jgpm train --model gpdm --max-iterations 3
        np.testing.assert_array_equal(model.latent, command.latent)
        xs = command.latent[::50] + 0.1
        np.testing.assert_array_equal(model.mean_pose(xs), command.mean_pose(xs))
        self.assertGreaterEqual(len(reports), 2)
        self.assertEqual([r["iteration"] for r in reports], sorted(r["iteration"] for r in reports))
        self.assertLess(reports[-1]["objective"], reports[0]["objective"])
        saved = self.dir / "saved.json"
        model.save(saved)
        np.testing.assert_array_equal(jgpm.load_model(saved).latent, model.latent)

    def test_an_exception_in_progress_stops_training_and_is_raised(self):
        class Enough(Exception):
            pass

        def progress(report):
            if report["iteration"] >= 1:
                raise Enough("enough")

        with self.assertRaises(Enough):
            jgpm.train("gpdm", data=str(self.data), max_iterations=50, progress=progress)
        with self.assertRaises(jgpm.InputError) as caught:
            jgpm.train("gpcm", data=str(self.data))
        self.assertIn("expected one of", str(caught.exception))

    def test_inference_fills_in_a_missing_leg(self):
        model = jgpm.load_model(self.models["gpdm"])
        saved = json.loads(Path(self.models["gpdm"]).read_text())["model"]
        poses = np.array(saved["training_poses_deg"])[:30]  # the first training cycle
        full = jgpm.infer(model, poses)
        self.assertLess(full["final_objective"], full["initial_objective"])
        self.assertEqual(full["latent"].shape, (30, 3))
        self.assertLess(np.abs(full["poses_deg"] - poses).mean(), 3)
        leg = [i for i, name in enumerate(model.channel_names) if name.split(".")[0] in ("lfemur", "ltibia", "lfoot")]
        observed = [i not in leg for i in range(model.num_channels)]
        missing = jgpm.infer(model, np.where(observed, poses, 0.0), observed=observed)
        # The left leg was never seen; the prior puts it within a few degrees of where it was.
        self.assertLess(np.abs(missing["poses_deg"][:, leg] - poses[:, leg]).mean(), 6)
        with self.assertRaises(TypeError):
            jgpm.infer(model, poses, observed=observed[:5])


class CalibrateTest(Fixture):
    def test_calibration_from_walkers_is_the_commands(self):
        # Eight walks seen by one surveillance camera (4.5 m up, 32 degrees down), each walk
        # elsewhere on the floor: the rig turned about the vertical and moved along its view.
        tilt, yaw = np.radians(32), None
        z = np.array([0.0, -np.sin(tilt), np.cos(tilt)])
        x = np.cross(z, [0.0, 1.0, 0.0])
        x /= np.linalg.norm(x)
        base = np.array([x, np.cross(z, x), z])  # rows: the camera's axes in the world
        clips = []
        trials = ["07/07_02", "07/07_03", "35/35_12", "35/35_16", "39/39_12", "02/02_01", "39/39_13", "07/07_04"]
        for k, trial in enumerate(trials):
            yaw = np.radians((k * 67) % 360)
            turn = np.array([[np.cos(yaw), 0, np.sin(yaw)], [0, 1, 0], [-np.sin(yaw), 0, np.cos(yaw)]])
            centre = turn @ np.array([0.0, 4500.0, -(9500.0 + (k % 4) * 2500.0 - 4000.0)])
            rotation = base @ turn.T
            camera = self.dir / f"walk{k}.yaml"
            camera.write_text(CameraTest.yaml(rotation, -rotation @ centre))
            clip = self.dir / f"walk{k}"
            run_jgpm("render", "--amc", self.data / "subjects" / f"{trial}.amc", "--camera", camera,
                     "--max-frames", 90, "--no-contact-sheet", "--out", clip)
            clips.append(str(clip))
        arguments = [a for clip in clips for a in ("--walkers", clip)]
        out = self.dir / "walkers.yaml"
        command = subprocess.run([BINARY, "calibrate", *arguments, "--out", str(out)], capture_output=True, text=True)
        if command.returncode != 0:  # refused: the same refusal
            with self.assertRaises(jgpm.InputError) as caught:
                jgpm.calibrate_from_walkers([[clip] for clip in clips])
            self.assertIn(str(caught.exception), command.stderr)
            return
        found = jgpm.calibrate_from_walkers([[clip] for clip in clips])
        self.assertEqual(len(found), 1)
        expected = jgpm.Camera.from_yaml(str(out))
        self.assertAlmostEqual(found[0].fx, expected.fx, places=9)
        np.testing.assert_allclose(found[0].rotation, expected.rotation, atol=1e-12)
        np.testing.assert_allclose(found[0].translation_mm, expected.translation_mm, atol=1e-9)


class TrackVideoTest(Fixture):
    def test_track_video_is_the_commands_run(self):
        clip, out = self.dir / "video_clip", self.dir / "video_tracked"
        run_jgpm("render", "--amc", self.data / "subjects" / "35" / "35_12.amc", "--max-frames", 20,
                 "--no-contact-sheet", "--out", clip)
        names = sorted(p.stem for p in clip.glob("cam*.yaml"))[:2]
        videos = [str(clip / f"{n}.avi") for n in names]
        yamls = [str(clip / f"{n}.yaml") for n in names]
        arguments = [a for v, c in zip(videos, yamls) for a in ("--video", v, "--camera", c)]
        run_jgpm("track", "--model", self.models["jgpm"], *arguments, "--seed", 4, "--no-overlay", "--out", out)
        written = json.loads((out / "poses.json").read_text())
        expected = written["frames"]
        result = jgpm.track_video(self.models["jgpm"], videos, yamls, seed=4, threads=1)
        self.assertEqual(result["shadow_light"], written["summary"]["shadow_light"])
        self.assertEqual(result["foreground_share"], written["summary"]["foreground_share"])
        self.assertEqual(sorted(result["foreground_share"]), names)
        self.assertEqual(len(result["frames"]), len(expected))
        for e, f in zip(result["frames"], expected):
            self.assertEqual((e["frame"], e["status"]), (f["frame"], f["status"]))
            if f["joints_mm"] is not None:
                np.testing.assert_allclose(e["joints_mm"], f["joints_mm"], atol=0.006)
        self.assertGreater(result["wall_seconds"], result["tracking_seconds"])
        self.assertEqual(result["written"], [])  # no out=: nothing written
        with self.assertRaises(jgpm.InputError) as caught:
            jgpm.track_video(self.models["jgpm"], videos, yamls[:1])
        self.assertIn("--camera", str(caught.exception))
        with self.assertRaises(jgpm.InputError) as caught:
            jgpm.track_video(self.models["jgpm"], videos, yamls, occluders=[yamls[0]])
        self.assertIn("--occluders", str(caught.exception))


    def test_everyone_in_view_with_people_all(self):
        clip, out = self.dir / "two_walkers", self.dir / "two_tracked"
        amc = self.data / "subjects" / "07" / "07_01.amc"
        run_jgpm("render", "--amc", amc, "--amc", amc, "--walk", "0,0,0,0", "--walk", "0,2000,0,0", "--max-frames", 20,
                 "--body-seed", 3, "--no-contact-sheet", "--out", clip)
        names = sorted(p.stem for p in clip.glob("cam*.yaml"))
        videos = [str(clip / f"{n}.avi") for n in names]
        yamls = [str(clip / f"{n}.yaml") for n in names]
        arguments = [a for v, c in zip(videos, yamls) for a in ("--video", v, "--camera", c)]
        run_jgpm("track", "--model", self.models["jgpm"], *arguments, "--seed", 4, "--no-overlay", "--people", "all",
                 "--out", out)
        expected = json.loads((out / "poses.json").read_text())["frames"]
        result = jgpm.track_video(self.models["jgpm"], videos, yamls, seed=4, threads=1, people="all")
        self.assertEqual(len(result["frames"]), len(expected))
        for e, f in zip(result["frames"], expected):
            self.assertEqual([(p["id"], p["status"]) for p in e["people"]], [(p["id"], p["status"]) for p in f["people"]])
            self.assertEqual((e["born"], e["ended"]), (f["born"], f["ended"]))
        self.assertEqual({p["id"] for e in result["frames"] for p in e["people"]}, {1, 2})  # the two walkers
        with self.assertRaises(jgpm.InputError) as caught:
            jgpm.track_video(self.models["jgpm"], videos, yamls, people="some")
        self.assertIn("people", str(caught.exception))


class TrackerTest(Fixture):
    def step_observed_masks(self, tracker, clip, names, count, given_at=14):
        """The clip's first `count` frames of observed masks stepped through `tracker`: the
        frames it returned, none until frame `given_at`, then all so far, then one a call: the
        start looks at 15 frames (given_at 14). One person's start is also gone back over a
        second after it, once its leg order is settled (30 at 30 frames/s, and the other
        order's trial, begun a walking cycle after the start, decided 10 frames later):
        `given_at` (first, last) for a frame between them."""
        import cv2
        first, last = given_at if isinstance(given_at, tuple) else (given_at, given_at)
        frames = []
        for k in range(count):
            masks = [cv2.imread(str(clip / "observed" / name / f"{k:06d}.png"), cv2.IMREAD_GRAYSCALE) for name in names]
            got = tracker.step(masks)
            if not frames:
                self.assertEqual(len(got), 0 if k < first else k + 1 if got or k >= last else 0, f"frame {k}")
            else:
                self.assertEqual(len(got), 1, f"frame {k}")
            frames += got
            for f in got:  # estimates of frames returned before, new or in place of the person's there
                for q in f.get("earlier", []):
                    at = next(e for e in frames if e["frame"] == q["frame"])
                    others = [p for p in at["people"] if p["id"] != q["id"]]
                    at["people"] = sorted(others + [q], key=lambda p: p["id"])
                    if q["id"] in f["born"]:
                        f["born"].remove(q["id"])
                        at["born"].append(q["id"])
        self.assertEqual(tracker.finish(), [])
        return frames

    def test_stepping_a_clips_masks_gives_the_commands_poses(self):
        clip, out = self.dir / "clip", self.dir / "tracked"
        run_jgpm("render", "--amc", self.data / "subjects" / "35" / "35_12.amc", "--max-frames", 40,
                 "--no-contact-sheet", "--out", clip)
        run_jgpm("track", "--model", self.models["jgpm"], "--clip", clip, "--seed", 2, "--no-overlay", "--out", out)
        expected = json.loads((out / "poses.json").read_text())["frames"]
        names = sorted(p.stem for p in clip.glob("cam*.yaml"))
        cameras = [jgpm.Camera.from_yaml(str(clip / f"{name}.yaml")) for name in names]
        tracker = jgpm.Tracker(jgpm.load_model(self.models["jgpm"]), cameras, seed=2, threads=1)
        estimates = self.step_observed_masks(tracker, clip, names, len(expected), given_at=(30, 39))
        self.assertEqual(len(estimates), len(expected))
        tracked = 0
        for e, f in zip(estimates, expected):
            self.assertEqual((e["frame"], e["status"]), (f["frame"], f["status"]))
            if f["joints_mm"] is None:
                self.assertIsNone(e["joints_mm"])
                continue
            tracked += 1
            # poses.json rounds to 0.01 mm; 1 thread here, all cores there.
            np.testing.assert_allclose(e["joints_mm"], f["joints_mm"], atol=0.006)
            self.assertAlmostEqual(e["heading_deg"], f["heading_deg"], places=6)
        self.assertGreater(tracked, 20)
        self.assertEqual(len(tracker.joint_names), len(estimates[-1]["joints_mm"]))

    def test_stepping_people_all_gives_the_commands_people(self):
        clip, out = self.dir / "two_clip", self.dir / "two_people"
        amc = self.data / "subjects" / "07" / "07_01.amc"
        run_jgpm("render", "--amc", amc, "--amc", amc, "--walk", "0,0,0,0", "--walk", "0,2000,0,0", "--max-frames", 40,
                 "--body-seed", 3, "--no-contact-sheet", "--out", clip)
        run_jgpm("track", "--model", self.models["jgpm"], "--clip", clip, "--seed", 2, "--no-overlay", "--people", "all",
                 "--out", out)
        expected = json.loads((out / "poses.json").read_text())["frames"]
        names = sorted(p.stem for p in clip.glob("cam*.yaml"))
        cameras = [jgpm.Camera.from_yaml(str(clip / f"{name}.yaml")) for name in names]
        tracker = jgpm.Tracker(jgpm.load_model(self.models["jgpm"]), cameras, seed=2, threads=1, people="all")
        frames = self.step_observed_masks(tracker, clip, names, len(expected))
        self.assertEqual(len(frames), len(expected))
        for e, f in zip(frames, expected):
            self.assertEqual((e["frame"], e["born"], e["ended"]), (f["frame"], f["born"], f["ended"]))
            self.assertEqual([(p["id"], p["status"]) for p in e["people"]], [(p["id"], p["status"]) for p in f["people"]])
            for p, q in zip(e["people"], f["people"]):
                if q["joints_mm"] is not None:
                    np.testing.assert_allclose(p["joints_mm"], q["joints_mm"], atol=0.006)
        self.assertEqual({p["id"] for e in frames for p in e["people"]}, {1, 2})  # the two walkers
        with self.assertRaises(jgpm.InputError) as caught:
            jgpm.Tracker(jgpm.load_model(self.models["jgpm"]), cameras, people="some")
        self.assertIn("people", str(caught.exception))

    def test_masks_of_the_wrong_size_or_number_are_refused(self):
        camera = self.dir / "cam.yaml"
        camera.write_text(CameraTest.yaml())
        tracker = jgpm.Tracker(jgpm.load_model(self.models["pca"]), [jgpm.Camera.from_yaml(str(camera))])
        with self.assertRaises(TypeError) as caught:
            tracker.step([np.zeros((240, 320), np.uint8)])
        self.assertIn("masks[0]: expected 480 x 640", str(caught.exception))
        with self.assertRaises(TypeError) as caught:
            tracker.step([np.zeros((480, 640), bool)] * 2)
        self.assertIn("one per camera (1), got 2", str(caught.exception))
        self.assertEqual(tracker.step(None), [])  # a frame not seen: held for the start like any other


class ExampleTest(Fixture):
    def test_the_example_sees_a_walk_through_a_camera(self):
        # 4 m in front of the walker's pelvis (the origin), looking at it along -z: image
        # right is world +x, image down world -y.
        camera = self.dir / "front.yaml"
        rotation = np.diag([1.0, -1.0, -1.0])
        camera.write_text(CameraTest.yaml(rotation, -rotation @ np.array([0.0, 0.0, 4000.0])))
        out, clip = self.dir / "walk.csv", self.dir / "example_clip"
        run_jgpm("render", "--amc", self.data / "subjects" / "35" / "35_12.amc", "--max-frames", 20,
                 "--no-contact-sheet", "--out", clip)
        printed = subprocess.run([sys.executable, SOURCE / "tracker" / "python" / "example.py", self.models["jgpm"],
                                  camera, out, clip], capture_output=True, text=True, check=True).stdout
        self.assertIn("60 frames", printed)
        tracked = re.search(r"(\d+) of 20 frames tracked, root ([0-9.]+) mm off", printed)
        self.assertIsNotNone(tracked, printed)
        self.assertGreater(int(tracked.group(1)), 15)
        self.assertLess(float(tracked.group(2)), 300)  # a 3-iteration prior, 20 frames
        rows = out.read_text().splitlines()
        self.assertEqual(len(rows), 61)
        # The walker stands in front of the camera: every joint in the image.
        values = np.array([[float(v) for v in row.split(",")[1:]] for row in rows[1:]])
        self.assertTrue(np.all((values[:, 0::2] > 0) & (values[:, 0::2] < 640)))
        self.assertTrue(np.all((values[:, 1::2] > 0) & (values[:, 1::2] < 480)))


class CameraTest(unittest.TestCase):
    @staticmethod
    def yaml(rotation=None, translation=(120.0, 900.0, 4000.0)):
        """A 640x480 camera with lens distortion; by default 4 m from the origin, turned and tilted."""
        import cv2
        if rotation is None:
            rotation, _ = cv2.Rodrigues(np.array([2.9, 0.2, -0.1]))
        numbers = lambda values: ", ".join(repr(float(v)) for v in np.ravel(values))
        return f"""%YAML:1.0
---
camera_name: "side"
image_width: 640
image_height: 480
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 520., 0., 318.5, 0., 515., 241.25, 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ -0.21, 0.06, 0.001, -0.0015, 0.01 ]
cam_from_world_rotation: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ {numbers(rotation)} ]
cam_from_world_translation_mm: !!opencv-matrix
   rows: 3
   cols: 1
   dt: d
   data: [ {numbers(translation)} ]
clock_offset_s: 0.25
"""

    def test_projection_is_opencvs(self):
        import cv2
        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "side.yaml"
            path.write_text(self.yaml())
            camera = jgpm.Camera.from_yaml(str(path))
        self.assertEqual((camera.name, camera.width, camera.height), ("side", 640, 480))
        self.assertEqual(camera.clock_offset_s, 0.25)
        points = np.random.default_rng(2).uniform([-1500, 0, -1500], [1500, 1800, 1500], size=(200, 3))
        rvec, _ = cv2.Rodrigues(camera.rotation)
        expected, _ = cv2.projectPoints(points, rvec, camera.translation_mm, camera.camera_matrix,
                                        np.array(camera.distortion))
        np.testing.assert_allclose(camera.project(points), expected.reshape(-1, 2), atol=1e-6)
        np.testing.assert_allclose(camera.project(points[5]), expected[5, 0], atol=1e-6)
        np.testing.assert_allclose(camera.centre_mm, -camera.rotation.T @ camera.translation_mm)
        behind = camera.centre_mm - 1000 * camera.rotation[2]  # a metre behind the camera
        self.assertTrue(np.all(np.isnan(camera.project(behind))))

    def test_a_bad_yaml_names_its_key(self):
        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "bad.yaml"
            path.write_text(self.yaml().replace("clock_offset_s: 0.25", "clock_offset_s: late"))
            with self.assertRaises(jgpm.InputError) as caught:
                jgpm.Camera.from_yaml(str(path))
            self.assertIn("bad.yaml", str(caught.exception))
            self.assertIn("clock_offset_s", str(caught.exception))


if __name__ == "__main__":
    unittest.main()
