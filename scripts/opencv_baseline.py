#!/usr/bin/env python3
"""OpenCV StereoBM / StereoSGBM baseline (a copy of the project's shared tools/opencv_baseline.py; reads
the ground truth's scale per file as sim::eval::io::scale_for does) on the pairs in DATA_DIR/<name>/ (one folder per pair with meta.txt).

Usage:  python baseline.py [DATA_DIR] [--threads N]   (default DATA_DIR = directory of this script,
        --threads 1 = single-threaded timing; 0 = OpenCV default thread pool)
Needs:  pip install numpy opencv-python-headless==4.12.0.88 (other 4.x/5.x behave the same)

Per pair (read from meta.txt): grey inputs left_gray.png / right_gray.png, GT disparity for the LEFT view,
convention d = xL - xR, GT scale factor, ndisp_opencv (= dispmax+1 rounded up to a multiple of 16).
Metrics (Middlebury style, error threshold strictly greater than t):
  eval set E   = pixels with valid GT (value > 0 / finite); "nonocc" rows also require nonocc.png > 127
  bad1, bad2   = % of E with |d - gt| > 1 (resp. 2) px, pixels WITHOUT an output disparity counted as bad
  bad1v, bad2v = % of E ∩ {output valid} with |d - gt| > 1 (resp. 2) (errors only where the method answered)
  density      = % of all image pixels that received a disparity (OpenCV invalid = (minDisparity-1)*16)
  ms           = median of 5 timed compute() calls (after 1 warm-up), image loading excluded
"""
import os, sys, time, csv, statistics
import numpy as np
import cv2

ROOT = os.path.dirname(os.path.abspath(__file__))
args = [a for a in sys.argv[1:]]
threads = 1
if '--threads' in args:
    i = args.index('--threads'); threads = int(args[i + 1]); del args[i:i + 2]
if args:
    ROOT = args[0]
if threads > 0:
    cv2.setNumThreads(threads)


def meta(d):
    m = {}
    for line in open(os.path.join(d, 'meta.txt')):
        if ':' in line:
            k, v = line.split(':', 1); m[k.strip()] = v.strip()
    return m


def load_gt(d, m):
    if os.path.exists(os.path.join(d, 'disp_gt.npz')):
        a = np.load(os.path.join(d, 'disp_gt.npz'))['arr_0'].astype(np.float32)
        v = np.isfinite(a) & (a > 0)
        return np.where(v, a, 0).astype(np.float32), v
    f = [x for x in os.listdir(d) if x.startswith('disp_gt.') and x.endswith(('.pgm', '.png'))][0]
    a = cv2.imread(os.path.join(d, f), cv2.IMREAD_UNCHANGED).astype(np.float32)
    # `scale` may name one value per file ("1 (npz float) ; 256 (disp_gt.png)"):
    # take the part that names this file, else the first number (as sim::eval::io::scale_for).
    parts = [p for p in m['scale'].split(';') if f in p] or [m['scale']]
    scale = float(parts[0].split()[0])
    return a / scale, a > 0


def make_bm(nd):
    bm = cv2.StereoBM_create(numDisparities=nd, blockSize=9)       # opencv samples/cpp/stereo_match.cpp defaults
    bm.setPreFilterCap(31); bm.setMinDisparity(0); bm.setTextureThreshold(10)
    bm.setUniquenessRatio(15); bm.setSpeckleWindowSize(100); bm.setSpeckleRange(32); bm.setDisp12MaxDiff(1)
    return bm


def make_sgbm(nd):
    bs, cn = 3, 1
    return cv2.StereoSGBM_create(minDisparity=0, numDisparities=nd, blockSize=bs,
                                 P1=8 * cn * bs * bs, P2=32 * cn * bs * bs, disp12MaxDiff=1,
                                 preFilterCap=63, uniquenessRatio=10, speckleWindowSize=100,
                                 speckleRange=32, mode=cv2.STEREO_SGBM_MODE_SGBM)


def timed(matcher, L, R, n=5):
    out = matcher.compute(L, R)  # warm-up
    ts = []
    for _ in range(n):
        t0 = time.perf_counter(); out = matcher.compute(L, R); ts.append((time.perf_counter() - t0) * 1e3)
    return out, statistics.median(ts)


def scores(raw, gt, gv, mask):
    d = raw.astype(np.float32) / 16.0
    ok = raw >= 0                                  # minDisparity = 0 -> invalid marked -16
    E = gv & mask
    err = np.abs(d - gt)
    n = max(int(E.sum()), 1)
    bad = lambda t: 100.0 * np.sum(E & (~ok | (err > t))) / n
    Ev = E & ok
    nv = max(int(Ev.sum()), 1)
    bad1v = 100.0 * np.sum(Ev & (err > 1)) / nv
    bad2v = 100.0 * np.sum(Ev & (err > 2)) / nv
    return dict(bad1=bad(1), bad2=bad(2), bad1v=bad1v, bad2v=bad2v, density=100.0 * ok.mean(), n_eval=int(E.sum()))


rows = []
names = sorted(x for x in os.listdir(ROOT) if os.path.isfile(os.path.join(ROOT, x, 'meta.txt')))
for name in names:
    d = os.path.join(ROOT, name); m = meta(d)
    L = cv2.imread(os.path.join(d, 'left_gray.png'), cv2.IMREAD_GRAYSCALE)
    R = cv2.imread(os.path.join(d, 'right_gray.png'), cv2.IMREAD_GRAYSCALE)
    gt, gv = load_gt(d, m)
    nd = int(m['ndisp_opencv'].split()[0])
    masks = {'all': np.ones_like(gv)}
    if os.path.exists(os.path.join(d, 'nonocc.png')):
        masks['nonocc'] = cv2.imread(os.path.join(d, 'nonocc.png'), cv2.IMREAD_GRAYSCALE) > 127
    for alg, make in (('BM', make_bm), ('SGBM', make_sgbm)):
        raw, ms = timed(make(nd), L, R)
        for region, mk in masks.items():
            s = scores(raw, gt, gv, mk)
            rows.append(dict(pair=name, size=f'{L.shape[1]}x{L.shape[0]}', ndisp=nd, alg=alg, region=region,
                             ms=round(ms, 2), threads=cv2.getNumThreads(), **{k: (round(v, 2) if isinstance(v, float) else v) for k, v in s.items()}))

out_csv = os.path.join(ROOT, f'baseline_results_threads{threads}.csv')
with open(out_csv, 'w', newline='') as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys())); w.writeheader(); w.writerows(rows)
print(f'OpenCV {cv2.__version__}, numpy {np.__version__}, cv2 threads {cv2.getNumThreads()} -> {out_csv}')
print('| pair | region | ndisp | BM bad1 | BM bad2 | BM bad2v | BM dens | BM ms | SGBM bad1 | SGBM bad2 | SGBM bad2v | SGBM dens | SGBM ms |')
print('|---|---|---|---|---|---|---|---|---|---|---|---|---|')
for name in names:
    for region in ('all', 'nonocc'):
        r = {x['alg']: x for x in rows if x['pair'] == name and x['region'] == region}
        if not r: continue
        b, s = r['BM'], r['SGBM']
        print(f"| {name} | {region} | {b['ndisp']} | {b['bad1']:.1f} | {b['bad2']:.1f} | {b['bad2v']:.1f} | {b['density']:.1f} | {b['ms']:.1f} "
              f"| {s['bad1']:.1f} | {s['bad2']:.1f} | {s['bad2v']:.1f} | {s['density']:.1f} | {s['ms']:.1f} |")
for region in ('all',):
    for alg in ('BM', 'SGBM'):
        sel = [x for x in rows if x['alg'] == alg and x['region'] == region]
        print(f"mean over {len(sel)} pairs ({region}) {alg}: bad1 {np.mean([x['bad1'] for x in sel]):.1f}  bad2 {np.mean([x['bad2'] for x in sel]):.1f}  "
              f"bad2v {np.mean([x['bad2v'] for x in sel]):.1f}  density {np.mean([x['density'] for x in sel]):.1f}  ms {np.mean([x['ms'] for x in sel]):.1f}")
