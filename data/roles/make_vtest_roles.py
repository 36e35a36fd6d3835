#!/usr/bin/env python3
"""Writes vtest_roles.csv: hand-assigned roles on bodyrec's own tracked boxes of vtest.avi.

How the labels were made (see README.md here): watching vtest.avi (PETS 2009 S2.L1) with the PETS
identities drawn, two pairs walk together: PETS persons 11 and 12 for the whole time they are in view,
and persons 9 and 15 from frame 20 to 205 (they stand together, then set off together; after frame 205
they walk apart). Everyone else walks alone. The leader of each pair is the one ahead when they walk off
(12 of 11-12, 15 of 9-15; the thesis's leader is permanent). These identity-level labels are the hand
labels; this script only puts them on boxes: every 10th frame, each of bodyrec's tracked boxes (from
`bodyrec track` or `bodyrec groups` JSONL) that overlaps a PETS box with IoU >= 0.5 gets the role of that
PETS identity. Boxes matching no person (false alarms) are left out. The PETS boxes themselves are not
written (the dataset is read, never copied).

Usage: make_vtest_roles.py TRACKS.jsonl PETS2009-S2L1.xml > vtest_roles.csv
"""
import json
import sys
import xml.etree.ElementTree as ET

GROUPS = [  # (leader, members, first frame, last frame)
    (12, [11], 0, 10**9),
    (15, [9], 20, 205),
]


def role_of(pets_id, frame):
    for leader, members, first, last in GROUPS:
        if first <= frame <= last:
            if pets_id == leader:
                return "leader"
            if pets_id in members:
                return "member"
    return "non-member"


def iou(a, b):
    ax, ay, aw, ah = a
    bx, by, bw, bh = b
    iw = max(0.0, min(ax + aw, bx + bw) - max(ax, bx))
    ih = max(0.0, min(ay + ah, by + bh) - max(ay, by))
    inter = iw * ih
    union = aw * ah + bw * bh - inter
    return inter / union if union > 0 else 0.0


def main():
    tracks, pets_xml = sys.argv[1], sys.argv[2]
    truth = {}
    for frame in ET.parse(pets_xml).getroot().iter("frame"):
        n = int(frame.get("number"))
        for obj in frame.iter("object"):
            b = obj.find("box")
            w, h = float(b.get("w")), float(b.get("h"))
            truth.setdefault(n, []).append((int(obj.get("id")), (float(b.get("xc")) - w / 2, float(b.get("yc")) - h / 2, w, h)))
    print("frame,x,y,w,h,role")
    for line in open(tracks):
        row = json.loads(line)
        n = row["frame"]
        if n % 10:
            continue
        boxes = [p["box"] for p in row.get("people", row.get("tracks", []))]
        used = set()
        for box in boxes:
            best, best_iou = None, 0.5
            for pid, tb in truth.get(n, []):
                if pid not in used and iou(box, tb) >= best_iou:
                    best, best_iou = pid, iou(box, tb)
            if best is None:
                continue
            used.add(best)
            print("%d,%.2f,%.2f,%.2f,%.2f,%s" % (n, box[0], box[1], box[2], box[3], role_of(best, n)))


if __name__ == "__main__":
    main()
