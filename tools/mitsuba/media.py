#!/usr/bin/env python3
"""media.py - the independent reference of ch. 11's media: renders
scenes/smoky-cbox.scn and scenes/cloud.scn with svet's volpath and with
Mitsuba 3's volpath (variant scalar_rgb), each at the same spp, and
compares them: the mean radiance of each channel over the image and over
each of 4 x 4 regions, within the noise, and the camera samples per second
of each, measured in one run, alternating. Writes the table (markdown) to
stdout. `make bench-media` runs it (bench/results/media.md).

The Mitsuba scenes are written out here from the svet scene files' numbers
(keep them in step). The conventions matched (Mitsuba 3 docs and
src/integrators/volpath.cpp):
- max_depth: Mitsuba's 1 renders only visible emitters, so svet's
  `maxdepth d` is Mitsuba's d + 1 (a medium scattering event counts as a
  bounce in both; crossing a null BSDF, svet's `invisible`, in neither).
- perspective: fov in degrees across fov_axis, as svet's; box film filter.
- rectangle: [-1, 1]^2 in z = 0 with normal +z; to_world maps it onto
  svet's parallelogram c0 c1 c3, the normal (c1 - c0) x (c3 - c0), the
  side an svet area light emits on.
- cube: [-1, 1]^3; svet's transforms apply in the order written, so
  to_world = translate @ rotate @ scale (both rotate counter-clockwise).
- homogeneous: sigma_t = sigma_a + sigma_s and albedo = sigma_s / sigma_t.
- heterogeneous: a gridvolume maps [0, 1]^3 by its to_world, values at the
  cell centres, clamped at the border, as svet's volgrid; the grid here
  holds density * sigma_t per channel (3 channels) and the albedo is a
  constant, which is exactly svet's density scaling both coefficients.
- hg: g > 0 scatters forward in both.
- walls reflect on both sides in svet: every diffuse BSDF is twosided.
- smoky-cbox's light: in Mitsuba an emitting rectangle with a null BSDF,
  its white reflection left to the ceiling 0.01 above it. Mitsuba 3's
  shadow ray from a point of a medium that crosses a null boundary (the
  smoke's top, 0.01 below the light) is stopped by the light's own
  surface when that has a non-null BSDF, so most of the direct light of
  the smoke just below the light went missing (single_scatter_check()
  shows it: its last column is that translation).
usage: media.py SVET [--spp N] [--rounds R]
"""
import os
import re
import struct
import subprocess
import sys
import tempfile
import time

import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")
# warnings (samples Mitsuba finds invalid) would go into the table
mi.set_log_level(mi.LogLevel.Error)
T = mi.ScalarTransform4f
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def diffuse(rgb):
    return {"type": "twosided",
            "b": {"type": "diffuse",
                  "reflectance": {"type": "rgb", "value": list(rgb)}}}


def parallelogram(c0, c1, c3, bsdf, emit=None):
    c0, c1, c3 = (np.array(v, float) for v in (c0, c1, c3))
    ex, ey = (c1 - c0) / 2, (c3 - c0) / 2
    ez = np.cross(ex, ey)
    ez /= np.linalg.norm(ez)
    centre = c0 + ex + ey
    m = np.identity(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = ex, ey, ez, centre
    d = {"type": "rectangle", "to_world": T(m.tolist()), "bsdf": bsdf}
    if emit is not None:
        d["emitter"] = {"type": "area",
                        "radiance": {"type": "rgb", "value": list(emit)}}
    return d


def box(lo, hi, **kw):
    lo, hi = np.array(lo, float), np.array(hi, float)
    d = {"type": "cube",
         "to_world": T().translate(((lo + hi) / 2).tolist()) @
                     T().scale(((hi - lo) / 2).tolist())}
    d.update(kw)
    return d


def camera(origin, target, up, fov, axis, w, h):
    return {"type": "perspective", "fov": fov, "fov_axis": axis,
            "to_world": T().look_at(origin=origin, target=target, up=up),
            "film": {"type": "hdrfilm", "width": w, "height": h,
                     "rfilter": {"type": "box"}, "pixel_format": "rgb"}}


def smoky_cbox(w, h):
    """scenes/smoky-cbox.scn"""
    white = diffuse((0.885809, 0.698859, 0.666422))
    green = diffuse((0.105421, 0.37798, 0.076425))
    red = diffuse((0.570068, 0.0430135, 0.0443706))
    s = {"type": "scene",
         "integrator": {"type": "volpath", "max_depth": 7 + 1,
                        "rr_depth": 3},
         "sensor": camera([0, 0, 3.9], [0, 0, 0], [0, 1, 0], 39.3077, "y",
                          w, h),
         "floor": parallelogram([-1, -1, 1], [1, -1, 1], [-1, -1, -1], white),
         "ceiling": parallelogram([-1, 1, -1], [1, 1, -1], [-1, 1, 1], white),
         "back": parallelogram([-1, -1, -1], [1, -1, -1], [-1, 1, -1], white),
         "right": parallelogram([1, -1, -1], [1, -1, 1], [1, 1, -1], green),
         "left": parallelogram([-1, -1, 1], [-1, -1, -1], [-1, 1, 1], red),
         # a null BSDF: see the opening comment
         "light": parallelogram([-0.23, 0.99, -0.18], [0.23, 0.99, -0.18],
                                [-0.23, 0.99, 0.2], {"type": "null"},
                                emit=(18.387, 13.9873, 6.75357)),
         "small": {"type": "cube", "bsdf": white,
                   "to_world": T().translate([0.335, -0.7, 0.38]) @
                               T().rotate([0, 1, 0], -17) @ T().scale(0.3)},
         "large": {"type": "cube", "bsdf": white,
                   "to_world": T().translate([-0.33, -0.4, -0.28]) @
                               T().rotate([0, 1, 0], 18.25) @
                               T().scale([0.3, 0.61, 0.3])},
         }
    sa, ss = 0.05, 0.5
    smoke = {"type": "homogeneous", "sigma_t": sa + ss,
             "albedo": {"type": "rgb", "value": [ss / (sa + ss)] * 3},
             "phase": {"type": "hg", "g": 0.3}}
    s["smoke"] = box([-0.999, -0.999, -0.999], [0.999, 0.98, 0.999],
                     bsdf={"type": "null"}, interior=smoke)
    return s


def read_vol(path):
    b = open(path, "rb").read()
    assert b[:4] == b"VOL\x03"
    enc, nx, ny, nz, nc = struct.unpack("<5i", b[4:24])
    assert enc == 1 and nc == 1
    v = np.frombuffer(b[48:], dtype="<f4").reshape(nz, ny, nx)
    return v.astype(np.float32)


def cloud(w, h):
    """scenes/cloud.scn"""
    s = {"type": "scene",
         "integrator": {"type": "volpath", "max_depth": 16 + 1,
                        "rr_depth": 3},
         "sensor": camera([0, 1.2, 5], [0, 0.8, 0], [0, 1, 0], 40, "x", w, h),
         "ground": parallelogram([-4, 0, 4], [4, 0, 4], [-4, 0, -4],
                                 diffuse((0.5, 0.45, 0.4))),
         "light": parallelogram([-1, 3, 1], [-1, 3, -1], [1, 3, 1],
                                diffuse((0, 0, 0)), emit=(12, 12, 12)),
         "sky": {"type": "constant",
                 "radiance": {"type": "rgb", "value": [0.1, 0.15, 0.25]}},
         }
    sa = np.array([0.2, 0.25, 0.3])
    ss = np.array([4.0, 4.0, 4.0])
    st = sa + ss
    dens = read_vol(os.path.join(ROOT, "scenes", "cloud.vol"))
    grid = np.ascontiguousarray(dens[..., None] * st[None, None, None, :],
                                dtype=np.float32)
    lo, hi = np.array([-1.5, 0.2, -1.0]), np.array([1.5, 1.6, 1.0])
    to_world = T().translate(lo.tolist()) @ T().scale((hi - lo).tolist())
    med = {"type": "heterogeneous",
           "sigma_t": {"type": "gridvolume", "grid": mi.VolumeGrid(grid),
                       "to_world": to_world, "filter_type": "trilinear"},
           "albedo": {"type": "rgb", "value": (ss / st).tolist()},
           "phase": {"type": "hg", "g": 0.3}}
    s["cloud"] = box(lo, hi, bsdf={"type": "null"}, interior=med)
    return s


SCENES = [("smoky-cbox", smoky_cbox, 128, 128), ("cloud", cloud, 160, 120)]


def read_exr(path):
    return np.array(mi.Bitmap(path).convert(
        mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32), dtype=np.float64)


def render_svet(svet, name, spp, seed, out):
    t0 = time.perf_counter()
    r = subprocess.run([svet, "render", os.path.join(ROOT, "scenes", name + ".scn"),
                        "--spp", str(spp), "--seed", str(seed), "--threads", "0",
                        "-o", out], capture_output=True, text=True, check=True)
    wall = time.perf_counter() - t0
    m = re.search(r"spp in ([0-9.]+) s", r.stderr + r.stdout)
    return read_exr(out), float(m.group(1)) if m else wall


def render_mitsuba(scene, spp, seed):
    t0 = time.perf_counter()
    img = mi.render(scene, spp=spp, seed=seed)
    return np.array(img, dtype=np.float64)[..., :3], time.perf_counter() - t0


def regions(img, n=4):
    """Per region of an n x n split: the mean of each channel and its
    standard error, the pixels' spread about the region's mean over
    sqrt(pixels). Pixel estimates are independent, and the spread about
    the region's mean counts the image's own variation across the region
    as noise too, so the error is an upper bound: the test is lenient
    where the region is not flat, never strict by mistake."""
    h, w, _ = img.shape
    out = []
    for j in range(n):
        for i in range(n):
            blk = img[j * h // n:(j + 1) * h // n, i * w // n:(i + 1) * w // n]
            blk = blk.reshape(-1, 3)
            out.append((blk.mean(0), blk.std(0, ddof=1) / np.sqrt(len(blk))))
    return out


def single_scatter_check(svet, tmp, spp=4096):
    """A third, independent answer near the smoky box's light: the box
    with only its light and its smoke (isotropic, maxdepth 1: single
    scattering of the light alone), at a few pixels, against the single-
    scattering integral by the midpoint rule, averaged over 4 x 4 rays
    across the pixel (the box filter), 1000 steps along each ray and
    120 x 100 on the light (halving either changes it by less than 1e-4
    of itself):
    L = int Tr(0, t) sigma_s (1 / 4 pi) int_A Le Tr(x, y) cos_l / r^2 dA dt,
    the transmittance to the light counting only the path inside the
    smoke (below y = 0.98)."""
    sa, ss, le, top = 0.05, 0.5, 18.387, 0.98
    st = sa + ss
    w = 32
    tanh = np.tan(np.radians(39.3077 / 2))

    def quad_ray(sx, sy):
        x = (2 * sx / w - 1) * tanh
        y = (1 - 2 * sy / w) * tanh
        d = np.array([x, y, -1.0])
        d /= np.linalg.norm(d)
        o = np.array([0, 0, 3.9])
        t0 = (0.999 - 3.9) / d[2]
        t1 = min(top / d[1] if d[1] > 0 else 1e9, (-0.999 - 3.9) / d[2])
        ts = np.linspace(t0, t1, 1001)
        lx, lz = np.linspace(-0.23, 0.23, 121), np.linspace(-0.18, 0.2, 101)
        gx, gz = np.meshgrid((lx[1:] + lx[:-1]) / 2, (lz[1:] + lz[:-1]) / 2)
        da = (lx[1] - lx[0]) * (lz[1] - lz[0])
        tot = 0.0
        for t in (ts[1:] + ts[:-1]) / 2:
            p = o + t * d
            v = np.stack([gx - p[0], np.full_like(gx, 0.99 - p[1]), gz - p[2]], -1)
            r2 = (v ** 2).sum(-1)
            r = np.sqrt(r2)
            g = le * np.exp(-st * r * (top - p[1]) / (0.99 - p[1])) * \
                (0.99 - p[1]) / r / r2 * da / (4 * np.pi)
            tot += np.exp(-st * (t - t0)) * ss * g.sum() * (ts[1] - ts[0])
        return tot

    def quad(px, py):
        # the box filter's pixel: the mean over its square, 4 x 4 rays
        return np.mean([quad_ray(px + (i + 0.5) / 4, py + (j + 0.5) / 4)
                        for j in range(4) for i in range(4)])

    def mitsuba_rounds(light_bsdf):
        sc = smoky_cbox(w, w)
        for k in ["floor", "ceiling", "back", "right", "left", "small", "large"]:
            del sc[k]
        sc["integrator"]["max_depth"] = 2
        sc["smoke"]["interior"]["phase"] = {"type": "isotropic"}
        if light_bsdf is not None:
            sc["light"]["bsdf"] = light_bsdf
        scene = mi.load_dict(sc)
        return [render_mitsuba(scene, spp // rounds, 1000 + k)[0]
                for k in range(rounds)]

    def mean_se(imgs):
        v = np.array(imgs)[..., 0]
        return v.mean(0), v.std(0, ddof=1) / np.sqrt(len(imgs))

    rounds = 16
    b = mean_se(mitsuba_rounds(None))
    # the earlier translation: the light white and diffuse, as in svet
    c = mean_se(mitsuba_rounds(diffuse((0.885809, 0.698859, 0.666422))))
    text = "".join(l for l in open(os.path.join(ROOT, "scenes", "smoky-cbox.scn"))
                   if not (l.startswith("parallelogram") and "emit" not in l)
                   and not l.startswith("box min -1"))
    text = text.replace("phase hg g 0.3", "").replace("maxdepth 7", "maxdepth 1")
    scn = os.path.join(ROOT, "scenes", ".media-single.scn")
    open(scn, "w").write(text)
    imgs = []
    try:
        for k in range(rounds):
            out = os.path.join(tmp, "single.exr")
            subprocess.run([svet, "render", scn, "--spp", str(spp // rounds),
                            "--seed", str(1000 + k), "--set",
                            "resolution=%dx%d" % (w, w), "-q", "-o", out],
                           check=True)
            imgs.append(read_exr(out))
    finally:
        os.remove(scn)
    a = mean_se(imgs)
    print("\nSingle scattering of the light alone (smoky-cbox.scn without its"
          " walls and boxes, isotropic, maxdepth 1, %d x %d, %d spp as %d"
          " rounds of independent seeds, +- one standard error of their"
          " mean), red channel at single pixels against the integral over"
          " the pixel (single_scatter_check()); the last column"
          " is Mitsuba with the light white and diffuse, as in svet:\n"
          % (w, w, spp, rounds))
    print("| pixel (x, y) | integral | svet | Mitsuba | Mitsuba, diffuse light |")
    print("|---|---:|---:|---:|---:|")
    for px, py in ((16, 3), (8, 3), (24, 3), (16, 6), (16, 16)):
        print("| %d, %d | %.4f | %s | %s | %s |"
              % ((px, py, quad(px, py)) +
                 tuple("%.4f +- %.4f" % (m[py, px], e[py, px])
                       for m, e in (a, b, c))))


def main():
    svet = sys.argv[1]
    spp, rounds = 64, 3
    args = sys.argv[2:]
    while args:
        k = args.pop(0)
        if k == "--spp":
            spp = int(args.pop(0))
        elif k == "--rounds":
            rounds = int(args.pop(0))
    tmp = tempfile.mkdtemp()
    cpu = "?"
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            cpu = line.split(":", 1)[1].strip()
            break
    print("Machine: %s, %d cores; Mitsuba %s (scalar_rgb), numpy %s.  "
          % (cpu, os.cpu_count(), mi.__version__, np.__version__))
    print("Command: `make bench-media` (tools/mitsuba/media.py %s --spp %d "
          "--rounds %d); date %s UTC; load average at the start %.2f %.2f"
          " %.2f (1, 5, 15 min).  " % ((svet, spp, rounds,
                                       time.strftime("%Y-%m-%d %H:%M", time.gmtime()))
                                      + os.getloadavg()))
    print("Both on every core, one run alternating svet and Mitsuba %d times"
          " per scene; samples/s from each one's fastest round (svet's own"
          " render time, Mitsuba's mi.render call); z: region mean"
          " difference over its standard error (see regions()).\n" % rounds)
    print("| scene | size | spp | svet samples/s | Mitsuba samples/s | ratio |"
          " whole image (svet / Mitsuba, per channel) | regions: max abs z | regions with abs z > 3 |")
    print("|---|---|---|---|---|---|---|---|---|")
    bad = 0
    for name, make, w, h in SCENES:
        scene = mi.load_dict(make(w, h))
        ts, tm, imgs, imgm = [], [], [], []
        for k in range(rounds):  # alternating: svet, Mitsuba, svet, ...
            a, t = render_svet(svet, name, spp, k, os.path.join(tmp, name + ".exr"))
            imgs.append(a)
            ts.append(t)
            b, t = render_mitsuba(scene, spp, k)
            imgm.append(b)
            tm.append(t)
        a, b = np.mean(imgs, 0), np.mean(imgm, 0)
        n = w * h * spp
        # the fastest round of each: the one least disturbed by other load
        rs, rm = n / min(ts), n / min(tm)
        zmax, nz = 0.0, 0
        for (ma, ea), (mb, eb) in zip(regions(a), regions(b)):
            # plus 0.1% of the mean: a region both see noiselessly (the
            # sky) differs by rounding alone
            se = np.sqrt(ea ** 2 + eb ** 2) + 1e-3 * np.abs(ma + mb) / 2
            z = np.abs(ma - mb) / np.maximum(se, 1e-30)
            zmax = max(zmax, float(z.max()))
            nz += int((z > 3).sum())
        ga, gb = a.reshape(-1, 3).mean(0), b.reshape(-1, 3).mean(0)
        whole = " ".join("%.4f/%.4f" % (x, y) for x, y in zip(ga, gb))
        print("| %s | %dx%d | %d x %d | %.3g | %.3g | %.2f | %s | %.2f | %d of 48 |"
              % (name, w, h, spp, rounds, rs, rm, rs / rm, whole, zmax, nz))
        bad += nz > 2
    # more than 2 of 48 beyond 3 standard errors (0.13 expected by chance)
    print("\nAgreement within the noise: %s." % ("yes" if not bad else
          "NO (a scene has more than 2 regions beyond 3 standard errors)"))
    single_scatter_check(svet, tmp)
    print("\nLoad average at the end: %.2f %.2f %.2f (1, 5, 15 min)."
          % os.getloadavg())
    return 0


if __name__ == "__main__":
    sys.exit(main())
