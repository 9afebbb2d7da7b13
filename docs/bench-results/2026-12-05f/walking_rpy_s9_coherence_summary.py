"""Per frame of the dump of walking_rpy_coherence_dump.patch (HBOS_DIAG=150, hbos-slam --tracker map,
default screen, no mask, rendered walking_rpy seed 9): the screen's noise scale and gate, and
the coherence evidence (a log-likelihood ratio) of the person's matches and of the room's.
usage: walking_rpy_s9_coherence_summary.py DUMP.txt"""
import sys
import numpy as np

frames, coherence, frame_scale = {}, [], None
for line in open(sys.argv[1]).read().splitlines():
    if line.startswith('F '):
        frame_scale, coherence = tuple(map(float, line.split()[1:])), []
    elif line.startswith('C '):
        coherence.append([float(x) for x in line.split()[1:]])
    elif line.startswith('M '):
        m = [float(x) for x in line.split()[1:]]
        frames.setdefault(int(m[0]), {'scale': frame_scale, 'C': coherence, 'M': []})['M'].append(m)
print('frame | noise scale | gate [px/sigma] | person matches | their coherence, median (kept ones) '
      '| room coherence, median / 90th percentile | person matches whose coherence contributes')
for f, r in sorted(frames.items()):
    C, M = np.array(r['C']), np.array(r['M'])
    person, kept = M[:, 1] == 1, M[:, 2] == 1
    coh = C[:, 0]
    print(f'{f} | {r["scale"][0]:.3f} | {r["scale"][1]:.3f} | {int(person.sum())} | '
          f'{np.nanmedian(coh[person]):.2f} ({np.nanmedian(coh[person & kept]):.2f}) | '
          f'{np.nanmedian(coh[~person]):.2f} / {np.nanpercentile(coh[~person], 90):.2f} | '
          f'{int((C[person, 2] > 0).sum())}')
