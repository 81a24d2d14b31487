#!/usr/bin/python3
"""Trains the learned pupil detector (model/gaze/learned_pupil_detector.h) on frames that
fovea-cli eye-dataset wrote, and exports it to ONNX for OpenCV's DNN module.

Input: one 96 x 96 grey frame (the 400 x 400 eye-camera frame downscaled with INTER_AREA),
scaled to x / 255 - 0.5. Output: 7 numbers, the pupil ellipse (cx, cy, major, minor in units
of the frame's width; cos 2a, sin 2a of the major axis' angle, the doubled angle because an
ellipse is symmetric under a half turn) and a logit whether a pupil is visible. The centre
comes from a 24 x 24 heatmap's soft-argmax (PupilNet's docstring); the axes, angle and
visibility are regressed from the flattened 6 x 6 map. Why no segmentation head: the ellipse
of an occluded or partly out-of-frame pupil is the *full* outline, which a segmentation of
the visible pixels does not give without a second fit that the lid edge biases; the soft-
argmax of a heatmap trained on the true centre points behind the lid as well. The C++ side
needs nothing beyond a forward pass, within the ops OpenCV 4.6's ONNX importer reads. The
classical fit refines the centre in `--detector auto`.

Usage: train_pupil_net.py --data DIR [--data DIR...] --val DIR --out model.onnx
       [--stage full|refine] [--epochs N] [--seed S] [--threads T] [--max-minutes M]
       [--occluded-repeats K] [--closed-weight W] [--context C] [--checkpoint PT] [--init PT]
       [--max-lr LR] [--scale-above LO:HI]
"""
import argparse
import csv
import json
import math
import os
import sys
import time

import numpy as np
import torch
import torch.nn as nn

SIZE = 96


def load(dirs, stored=SIZE):
    """Frames, targets (centre and axes as fractions of the frame width w), the mirror of a
    centre, (w - 1) / w (every directory's frames share w), and the visible fraction of each
    frame's pupil."""
    images, targets, widths, visible = [], [], set(), []
    for d in dirs:
        meta = json.load(open(os.path.join(d, "dataset.json")))
        w, h = meta["frame_size_px"]
        widths.add(w)
        s = meta["stored_size_px"][0]
        if s != stored:
            sys.exit(f"{d}: frames stored at {s} px, this stage reads {stored}")
        n = meta["frames"]
        img = np.fromfile(os.path.join(d, "images.u8"), dtype=np.uint8)
        if img.size != n * s * s:
            sys.exit(f"{d}/images.u8: {img.size} bytes, expected {n * s * s}")
        images.append(img.reshape(n, 1, s, s))
        rows = list(csv.DictReader(open(os.path.join(d, "labels.csv"))))
        t = np.zeros((n, 7), dtype=np.float32)
        for i, r in enumerate(rows):
            a = math.radians(float(r["angle_deg"]))
            t[i] = [float(r["cx_px"]) / w, float(r["cy_px"]) / h, float(r["major_px"]) / w,
                    float(r["minor_px"]) / w, math.cos(2 * a), math.sin(2 * a), float(r["visible"])]
        targets.append(t)
        visible.append(np.array([float(r["visible_fraction"]) for r in rows], dtype=np.float32))
    if len(widths) != 1:
        sys.exit(f"frames of several widths {sorted(widths)}: the flip needs one")
    w = widths.pop()
    return np.concatenate(images), np.concatenate(targets), (w - 1) / w, np.concatenate(visible)


def block(cin, cout, stride):
    return [nn.Conv2d(cin, cout, 3, stride, 1, bias=False), nn.BatchNorm2d(cout), nn.ReLU(inplace=True)]


GRID = 24  # the centre heatmap's cells: 96 / 4, 16.7 px of a 400 px frame each


class PupilNet(nn.Module):
    """An encoder (four stride-2 convolutions, 96 -> 6), a regression head on the flattened
    6 x 6 map for the axes, angle and visibility, and a decoder back to 24 x 24 (transposed
    convolutions with skips from the encoder) whose one-channel map is a centre heatmap read
    by its soft-argmax (integral regression, Sun et al., ECCV 2018): the expectation of the
    cell centres under the softmax of the map. The soft-argmax is differentiable and trained
    on the centre itself, so the centre is sub-cell (unlike an argmax) and translation-
    equivariant (unlike the dense head, whose 6 x 6 x 64 -> 128 layer regressed it to ~7 px).
    It is part of the graph (Flatten, Softmax, MatMul with the constant cell grid, Slice,
    Concat: ops OpenCV 4.6's ONNX importer reads), so the output stays the 7 numbers
    model/gaze/learned_pupil_detector.cpp reads."""

    def __init__(self, context=0):
        super().__init__()
        self.e1 = nn.Sequential(*block(1, 16, 2))  # 48
        self.e2 = nn.Sequential(*block(16, 32, 2))  # 24
        self.e3 = nn.Sequential(*block(32, 48, 2))  # 12
        # `context` stride-1 3 x 3 convolutions at 6 x 6 widen what each heatmap cell sees. The
        # encoder alone gives a 6 x 6 cell a receptive field of 31 input px (3, 7, 15, 31: each
        # stride-2 layer adds twice its input's stride) and a heatmap cell about 55 (the decoder's
        # two 3 x 3 layers add 16 and 8): in the refining stage, 2 frame px per input px, a cell
        # sees about 55 frame px around it, less than the radius of the largest pupils (major
        # axes to ~180 px), whose centre behind a lid is inferred from an arc a radius away. Each
        # convolution here adds 32 input px; with three (`--context 3`, both shipped stages) a 6 x 6
        # cell sees 127 px, the whole 96 px input: the refining stage's window, and the first
        # stage's whole frame (there a cell saw 31 input px, 129 frame px, before).
        self.e4 = nn.Sequential(*block(48, 64, 2), *[m for _ in range(context) for m in block(64, 64, 1)])  # 6
        self.head = nn.Sequential(nn.Flatten(), nn.Linear(64 * 6 * 6, 128), nn.ReLU(inplace=True), nn.Linear(128, 7))
        self.up1 = nn.ConvTranspose2d(64, 48, 2, 2)  # 6 -> 12, added to e3
        self.d1 = nn.Sequential(*block(48, 32, 1))
        self.up2 = nn.ConvTranspose2d(32, 32, 2, 2)  # 12 -> 24, added to e2
        self.d2 = nn.Sequential(*block(32, 16, 1), nn.Conv2d(16, 1, 1))
        c = (torch.arange(GRID, dtype=torch.float32) + 0.5) / GRID
        gy, gx = torch.meshgrid(c, c, indexing="ij")
        # The cell grid as a frozen bias-free linear layer (a registered buffer exports as an
        # Identity node, which OpenCV 4.6's importer refuses).
        self.grid = nn.Linear(GRID * GRID, 2, bias=False)
        self.grid.weight.data = torch.stack([gx.reshape(-1), gy.reshape(-1)], dim=0)  # (2, 576)
        self.grid.weight.requires_grad_(False)

    def forward(self, x):
        f2 = self.e2(self.e1(x))
        f3 = self.e3(f2)
        f4 = self.e4(f3)
        dense = self.head(f4)
        h = self.d1(self.up1(f4) + f3)
        heat = self.d2(self.up2(h) + f2)
        centre = self.grid(torch.softmax(torch.flatten(heat, 1), dim=1))
        return torch.cat([centre, dense[:, 2:]], dim=1)


def loss_fn(out, t, closed_weight):
    vis = t[:, 6]
    # Closed eyes weigh `closed_weight` (--closed-weight, 3 by default): a false pupil moves the display to a gaze
    # that is not there (issue 31: <= 1 % false positives on closed eyes).
    bce = nn.functional.binary_cross_entropy_with_logits(out[:, 6], vis, weight=1 + (closed_weight - 1) * (1 - vis))
    m = vis > 0.5
    if m.sum() == 0:
        return bce, bce
    o, g = out[m], t[m]
    # Centre in frame widths: 1 px of a 400 px frame is 0.0025; weight it most.
    centre = nn.functional.smooth_l1_loss(o[:, :2] * 100, g[:, :2] * 100, beta=0.25)
    axes = nn.functional.smooth_l1_loss(o[:, 2:4] * 100, g[:, 2:4] * 100, beta=0.5)
    ecc = (1 - g[:, 3] / g[:, 2].clamp(min=1e-6)).clamp(0, 1)  # the angle of a circle is moot
    angle = (ecc * ((o[:, 4] - g[:, 4]) ** 2 + (o[:, 5] - g[:, 5]) ** 2)).mean()
    return centre + 0.3 * axes + 0.5 * angle + 0.5 * bce, centre


def evaluate(model, x, t, px_per_unit=400, bs=512):
    """Centre errors in frame px (`px_per_unit`: frame px per unit of the outputs - the frame's
    width for the full-frame stage, each crop's span for the refining one)."""
    px_per_unit = np.broadcast_to(np.asarray(px_per_unit, dtype=np.float64), (len(x),))
    model.eval()
    errs, vis_ok, n_vis = [], 0, 0
    with torch.no_grad():
        for i in range(0, len(x), bs):
            xb = torch.from_numpy(x[i:i + bs]).float() / 255 - 0.5
            o = model(xb).numpy()
            tb = t[i:i + bs]
            pred_vis = o[:, 6] > 0
            vis_ok += int((pred_vis == (tb[:, 6] > 0.5)).sum())
            m = tb[:, 6] > 0.5
            errs.append(np.hypot(o[m, 0] - tb[m, 0], o[m, 1] - tb[m, 1]) * px_per_unit[i:i + bs][m])
    e = np.concatenate(errs)
    return {"centre_err_px_median": float(np.median(e)), "within_5px": float((e <= 5).mean()),
            "p90_px": float(np.percentile(e, 90)), "visibility_accuracy": vis_ok / len(x)}


# The refining stage (model/gaze/learned_pupil_detector.cpp runs it after the full-frame one):
# the frame downscaled to CANVAS x CANVAS (2 frame px per canvas px for the 400 px frames), a
# SIZE x SIZE window of it centred on the first stage's centre, edges replicated, and the same
# network regressing the ellipse in units of the window. Twice the full-frame stage's
# resolution on the pupil (4.17 frame px per input px there), at the cost of one more pass.
CANVAS = 200


def refine_crops(x, t, idx, proposal_px, w, canvas=None):
    """Windows of the CANVAS-px frames x[idx] around proposals (frame px, pixel centres at
    integers), the targets in window units and each window's span in frame px. `canvas` (one
    size per frame, CANVAS where None) shrinks a frame's canvas first: the CANVAS-px frame
    resized to c px with INTER_AREA, as model/gaze/learned_pupil_detector.cpp does (a scaled
    window, see scaled_canvas). Frame -> canvas: u = (X + 0.5) / s - 0.5 with s = w / c frame px
    per canvas px (OpenCV's resize maps pixel centres so, at any size); the window, whose centre
    is its start o + (SIZE - 1) / 2, starts at o = round(u - (SIZE - 1) / 2) (round half to even,
    symmetric: the window of a mirrored frame is the mirrored window), and a window fraction f is
    the canvas coordinate o + f SIZE - 0.5 (the soft-argmax grid's cell centres (i + 0.5) / GRID
    span the window's pixel edges), so f = ((X + 0.5) / s - o) / SIZE."""
    c = np.full(len(idx), CANVAS) if canvas is None else np.asarray(canvas)
    s = w / c
    o = np.rint((proposal_px + 0.5) / s[:, None] - 0.5 - (SIZE - 1) / 2).astype(np.int64)  # (B, 2): x, y
    ar = np.arange(SIZE)
    cols = np.clip(o[:, 0, None] + ar, 0, c[:, None] - 1)
    rows = np.clip(o[:, 1, None] + ar, 0, c[:, None] - 1)
    xb = np.empty((len(idx), 1, SIZE, SIZE), dtype=x.dtype)
    plain = c == CANVAS
    if plain.any():
        i = idx[plain]
        xb[plain] = x[i[:, None, None], 0, rows[plain][:, :, None], cols[plain][:, None, :]][:, None]
    for k in np.flatnonzero(~plain):
        import cv2  # python3-opencv, the C++ side's OpenCV 4.6: the same INTER_AREA weights
        small = cv2.resize(x[idx[k], 0], (int(c[k]), int(c[k])), interpolation=cv2.INTER_AREA)
        xb[k, 0] = small[rows[k][:, None], cols[k][None, :]]
    tb = t[idx].copy()
    tb[:, 0] = ((tb[:, 0] * w + 0.5) / s - o[:, 0]) / SIZE
    tb[:, 1] = ((tb[:, 1] * w + 0.5) / s - o[:, 1]) / SIZE
    tb[:, 2:4] *= (w / (s * SIZE))[:, None]
    return np.ascontiguousarray(xb), tb, s * SIZE


def scaled_canvas(gen, major_px, above):
    """The canvas each window is cut from when the refining stage's window scales with the pupil
    (--scale-above LO:HI): the proposed major axis (the true one times a log-normal factor of
    sd 0.07, the first stage's own spread on the validation frames) m above T frame px shrinks
    the canvas to round(CANVAS T / m) px (at least SIZE), so the pupil looks T px of the
    CANVAS-px canvas wide and the window spans more of the frame around it. T is drawn
    uniformly from [LO, HI] per window, so the C++ side's T (kRefineScaleAboveMajor, a fraction
    of the window's 192 frame px: T / 192) can be chosen within the trained range on held-out
    frames (scripts/refine-scale-sweep.py)."""
    if above is None:
        return None
    lo, hi = above
    m = major_px * np.exp(gen.normal(size=len(major_px)) * 0.07)
    T = gen.uniform(lo, hi, size=len(major_px))
    return np.where(m > T, np.maximum(SIZE, np.rint(CANVAS * T / np.maximum(m, 1e-6))), CANVAS).astype(np.int64)


def proposal_jitter(gen, n):
    """The full-frame stage's centre errors, roughly (its held-out p50 1.6-4.7 px, p90 up to 11 px
    on the hard subset): 70 % Gaussian of 3 px per axis, 30 % of 10 px, clipped to 40 px."""
    sd = np.where(gen.random(n) < 0.7, 3.0, 10.0)[:, None]
    return np.clip(gen.normal(size=(n, 2)) * sd, -40, 40)


def export(model, path):
    """ONNX for OpenCV 4.6: batch norm folded into the convolutions (constant folding). Two
    folded tensors that happen to be equal (e.g. zero biases) are exported as one initializer
    and an Identity node, which OpenCV 4.6 refuses; such nodes are replaced by copies."""
    torch.onnx.export(model, torch.zeros(1, 1, SIZE, SIZE), path, opset_version=11, input_names=["frame"],
                      output_names=["ellipse"], do_constant_folding=True)
    import onnx
    from onnx import numpy_helper
    m = onnx.load(path)
    inits = {i.name: i for i in m.graph.initializer}
    for n in [n for n in m.graph.node if n.op_type == "Identity" and n.input[0] in inits]:
        m.graph.initializer.append(numpy_helper.from_array(numpy_helper.to_array(inits[n.input[0]]), n.output[0]))
        m.graph.node.remove(n)
    onnx.save(m, path)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", action="append", required=True)
    ap.add_argument("--val", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--stage", choices=["full", "refine"], default="full")
    ap.add_argument("--epochs", type=int, default=30)
    ap.add_argument("--seed", type=int, default=31)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--max-minutes", type=float, default=20)
    ap.add_argument("--occluded-repeats", type=int, default=1,
                    help="times an epoch shows a frame whose pupil is less than 60 %% visible (default 1)")
    ap.add_argument("--closed-weight", type=float, default=3.0,
                    help="weight of a closed eye's visibility loss against an open one's 1 (default 3)")
    ap.add_argument("--context", type=int, default=0,
                    help="stride-1 convolutions at the 6 x 6 level (a wider receptive field; default 0)")
    ap.add_argument("--checkpoint", help="also save the trained weights (a PyTorch state dict) here, for --init")
    ap.add_argument("--init", help="start from these weights (a --checkpoint of the same stage) instead of random ones")
    ap.add_argument("--max-lr", type=float, default=3e-3,
                    help="the one-cycle schedule's peak learning rate (default 3e-3; lower to continue from --init)")
    ap.add_argument("--scale-above", metavar="LO:HI",
                    help="refining stage: shrink the canvas of a window whose proposed major axis m exceeds T frame "
                         "px, T drawn from [LO, HI] per window, to CANVAS T / m px (see scaled_canvas; default off)")
    a = ap.parse_args()
    if a.scale_above:
        try:
            lo, hi = (float(v) for v in a.scale_above.split(":"))
        except ValueError:
            sys.exit(f"--scale-above {a.scale_above}: LO:HI, two numbers of frame px (e.g. 90:150)")
        if not 0 < lo <= hi:
            sys.exit(f"--scale-above {a.scale_above}: LO:HI with 0 < LO <= HI")
        a.scale_above = (lo, hi)
    torch.manual_seed(a.seed)
    np.random.seed(a.seed)
    torch.set_num_threads(a.threads)
    refine = a.stage == "refine"
    stored = CANVAS if refine else SIZE
    x, t, mirror_x, vis = load(a.data, stored)
    xv, tv, _, _ = load([a.val], stored)
    # Each epoch's frames: all once, those with a pupil less than 60 % visible (the occluded and
    # hard subsets' range, where the centre is furthest behind the lid) `occluded_repeats` times.
    occluded = np.flatnonzero((t[:, 6] > 0.5) & (vis < 0.6))
    epoch_frames = np.concatenate([np.arange(len(x))] + [occluded] * (a.occluded_repeats - 1))
    w = round(1 / (1 - mirror_x))  # the frames' width
    gen = np.random.default_rng(a.seed)
    if refine:
        # Validation windows around fixed jittered proposals (their own seed); errors in frame px.
        vgen = np.random.default_rng(a.seed + 1)
        iv = np.arange(len(xv))
        proposals = tv[:, :2] * w + proposal_jitter(vgen, len(iv))
        xv, tv, px_per_unit = refine_crops(xv, tv, iv, proposals, w, scaled_canvas(vgen, tv[:, 2] * w, a.scale_above))
        mirror = 1.0  # window fractions mirror to 1 - f (see refine_crops)
    else:
        px_per_unit, mirror = w, mirror_x
    print(f"{a.stage} stage: train {len(x)} frames ({int(t[:, 6].sum())} with a pupil, {len(occluded)} of them "
          f"less than 60 % visible, shown {a.occluded_repeats}x an epoch), validation {len(xv)}", flush=True)
    model = PupilNet(a.context)
    if a.init:
        model.load_state_dict(torch.load(a.init))
    opt = torch.optim.AdamW(model.parameters(), lr=2e-3, weight_decay=1e-4)
    bs = 64
    steps = a.epochs * (len(epoch_frames) // bs)
    sched = torch.optim.lr_scheduler.OneCycleLR(opt, max_lr=a.max_lr, total_steps=steps, pct_start=0.15)
    start = time.time()
    step = 0
    for epoch in range(a.epochs):
        model.train()
        order = gen.permutation(epoch_frames)
        total = 0.0
        for i in range(0, len(order) - bs + 1, bs):
            idx = order[i:i + bs]
            if refine:
                proposals = t[idx, :2] * w + proposal_jitter(gen, len(idx))
                xi, tb, _ = refine_crops(x, t, idx, proposals, w, scaled_canvas(gen, t[idx, 2] * w, a.scale_above))
            else:
                xi, tb = x[idx], t[idx]
            xb = torch.from_numpy(xi).float() / 255 - 0.5
            if gen.random() < 0.5:  # horizontal flip: a mirrored eye is an eye (angle -> -angle)
                xb = torch.flip(xb, dims=[3])
                tb = tb.copy()
                # Pixel centres at integers (OpenCV's, the renderer's labels): a mirrored w-px
                # frame takes cx to (w - 1) - cx, i.e. x -> (w - 1) / w - x. (Until 2026-12-05 the
                # trainer used 1 - x: flipped labels 1 px off, a +0.5 px bias in x.) A refining
                # window's fractions are of its pixel edges: f -> 1 - f.
                tb[:, 0] = mirror - tb[:, 0]
                tb[:, 5] = -tb[:, 5]
            out = model(xb)
            loss, _ = loss_fn(out, torch.from_numpy(tb), a.closed_weight)
            opt.zero_grad()
            loss.backward()
            opt.step()
            if step < steps - 1:
                sched.step()
            step += 1
            total += float(loss)
        ev = evaluate(model, xv, tv, px_per_unit)
        mins = (time.time() - start) / 60
        print(f"epoch {epoch + 1}/{a.epochs}: loss {total / (len(order) // bs):.4f} val {ev} ({mins:.1f} min)",
              flush=True)
        if mins > a.max_minutes:
            print("time budget reached: stopping early", flush=True)
            break
    model.eval()
    if a.checkpoint:
        torch.save(model.state_dict(), a.checkpoint)
    export(model, a.out)
    ev = evaluate(model, xv, tv, px_per_unit)
    # docs/gaze-tracking.md prints these figures (scripts/doc-numbers.json holds it to this file)
    json.dump({"validation": ev, "train_minutes": (time.time() - start) / 60, "frames": len(x),
               "frames_with_pupil": int(t[:, 6].sum()), "validation_frames": len(xv),
               "epochs": epoch + 1, "seed": a.seed, "input_px": SIZE, "stage": a.stage,
               "occluded_repeats": a.occluded_repeats, "closed_weight": a.closed_weight,
               "frames_less_than_60pct_visible": int(len(occluded)), "init": bool(a.init), "max_lr": a.max_lr,
               "context_convs": a.context,
               **({"scale_above_px": list(a.scale_above)} if a.scale_above else {}),
               **({"canvas_px": CANVAS} if refine else {})}, open(a.out + ".json", "w"), indent=2)
    print(f"wrote {a.out} ({os.path.getsize(a.out)} bytes), validation {ev}")


if __name__ == "__main__":
    main()
