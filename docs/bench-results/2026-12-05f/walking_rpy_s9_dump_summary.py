"""Summary of the dump (walking_rpy_dump.patch, HBOS_DIAG=150) of hbos-slam --tracker map, default
screen, no mask, rendered walking_rpy seed 9: per frame, the person's and the room's matches,
how many the screen kept, how many are new points on probation, their whitened magnitudes.
usage: walking_rpy_s9_dump_summary.py DUMP.txt"""
import sys
import numpy as np
rows = [l.split()[1:] for l in open(sys.argv[1]) if l.startswith('M ')]
a = np.array([[float(x) for x in r] for r in rows])
print('frame | score cut t | person matches | kept | on probation | kept on probation | magnitude of kept person matches, quartiles [px/sigma] | room matches | kept | room magnitude, median')
for f in sorted(set(a[:, 0].astype(int))):
    b = a[a[:, 0] == f]
    per, room = b[b[:, 1] == 1], b[b[:, 1] == 0]
    kept = per[per[:, 2] == 1]
    q = np.percentile(kept[:, 3], [25, 50, 75]).round(2).tolist() if len(kept) else '-'
    print(f'{f} | {b[0, 5]} | {len(per)} | {len(kept)} | {int(per[:, 7].sum())} | {int(kept[:, 7].sum())} | {q} | '
          f'{len(room)} | {int(room[:, 2].sum())} | {np.median(room[:, 3]):.2f}')
