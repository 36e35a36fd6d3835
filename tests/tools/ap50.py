#!/usr/bin/env python3
"""Independent AP50 for a MOTChallenge detection file against PETS/CVML XML or MOT gt.txt.

Written apart from bodyrec's C++ code (standard library only) so the two can be checked against each
other. Detections are ranked by score over all frames; each is matched in its frame to a ground-truth
box with IoU >= 0.5. Two matching rules are computed:
  coco: the unmatched ground-truth box of highest IoU (pycocotools' rule, bodyrec's rule);
  voc:  the ground-truth box of highest IoU; a false positive if it is already taken (VOC devkit).
AP is the all-points interpolated area under the precision/recall curve (VOC 2010+).
Usage: ap50.py DETECTIONS.mot GT.xml|gt.txt [--frames N]   -> prints JSON {"coco": ap, "voc": ap, ...}
"""
import json
import sys
import xml.etree.ElementTree as ET


def read_gt(path, max_frames):
    gt = {}
    if path.endswith(".xml"):
        for frame in ET.parse(path).getroot().iter("frame"):
            f = int(frame.get("number"))
            for obj in frame.iter("object"):
                b = obj.find("box")
                w, h = float(b.get("w")), float(b.get("h"))
                gt.setdefault(f, []).append((float(b.get("xc")) - w / 2, float(b.get("yc")) - h / 2, w, h))
    else:
        for line in open(path):
            p = line.strip().split(",")
            if len(p) < 6:
                continue
            if len(p) > 6 and float(p[6]) == 0:
                continue
            if len(p) > 7 and float(p[7]) not in (1, -1):
                continue
            gt.setdefault(int(p[0]) - 1, []).append(tuple(map(float, p[2:6])))
    return {f: b for f, b in gt.items() if max_frames is None or f < max_frames}


def read_dets(path, max_frames):
    dets = []
    for line in open(path):
        p = line.strip().split(",")
        if len(p) < 7:
            continue
        f = int(p[0]) - 1
        if max_frames is None or f < max_frames:
            dets.append((float(p[6]), f, tuple(map(float, p[2:6]))))
    return dets


def iou(a, b):
    ix = max(0.0, min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0]))
    iy = max(0.0, min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1]))
    inter = ix * iy
    union = a[2] * a[3] + b[2] * b[3] - inter
    return inter / union if union > 0 else 0.0


def ap(dets, gt, rule):
    n_gt = sum(len(v) for v in gt.values())
    taken = {f: [False] * len(v) for f, v in gt.items()}
    order = sorted(range(len(dets)), key=lambda i: -dets[i][0])  # stable: file order among ties
    tps = []
    for i in order:
        _, f, box = dets[i]
        best, best_j = 0.5, -1
        for j, g in enumerate(gt.get(f, [])):
            if rule == "coco" and taken[f][j]:
                continue
            o = iou(box, g)
            if o >= best:
                best, best_j = o, j
        tp = best_j >= 0 and not taken[f][best_j]
        if tp:
            taken[f][best_j] = True
        tps.append(tp)
    prec, rec, tp = [], [], 0
    for k, t in enumerate(tps):
        tp += t
        prec.append(tp / (k + 1))
        rec.append(tp / n_gt)
    for k in range(len(prec) - 2, -1, -1):
        prec[k] = max(prec[k], prec[k + 1])
    area, prev = 0.0, 0.0
    for p, r in zip(prec, rec):
        area += (r - prev) * p
        prev = r
    return area, tp, n_gt


def main():
    args = sys.argv[1:]
    frames = None
    if "--frames" in args:
        k = args.index("--frames")
        frames = int(args[k + 1])
        del args[k:k + 2]
    gt = read_gt(args[1], frames)
    dets = read_dets(args[0], frames)
    coco, tp, n_gt = ap(dets, gt, "coco")
    voc, _, _ = ap(dets, gt, "voc")
    print(json.dumps({"coco": coco, "voc": voc, "detections": len(dets), "true_positives": tp, "ground_truth": n_gt}))


if __name__ == "__main__":
    main()
