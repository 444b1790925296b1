#!/usr/bin/env python3
"""The representations of the 3-5 um built-ins measured (docs/accuracy.md, "The 3-5 um built-ins").

usage: python mwir_representation.py /tmp/mwir/NAME/NAME.mwir-full.bin ...

For each regen.py --mwir output (NAME.mwir-full.bin, LOWTRAN7's f32 spectra every 5 cm-1, and
beside it NAME.mwir.bin, the committed version 2 form) it prints, for the committed form and
for every candidate, its bytes per model and the largest error in K against the full data:
apparent temperature of 260, 290 and 320 K blackbodies through every path (band model:
collapsed tau x band L(T) + collapsed path radiance) and the sky's brightness temperature,
over flat 3-5, 3.4-4.2, 4.5-5.0 and 3.7-4.8 um. numpy only."""
import struct, re, numpy as np
ORDER = ["level_transmission", "level_path_radiance", "cor_transmission", "sky_radiance",
         "sky_hemispheric", "slant_transmission", "slant_path_radiance", "slant_sky_radiance"]
def read(path):
    b = open(path, "rb").read()
    assert b[:8] == b"IRSIGSPA"
    v, n = struct.unpack("<II", b[8:16]); header = b[16:16+n].decode()
    off = 16 + n; tables = []
    while off < len(b):
        c, = struct.unpack("<I", b[off:off+4]); off += 4
        tables.append(np.frombuffer(b[off:off+4*c], dtype="<f4").copy()); off += 4*c
    m = re.search(r"points:\[([^\]]*)\]", header)
    grid = np.array([float(x) for x in m.group(1).split(",")])
    return header, grid, dict(zip(ORDER, tables))

def read_v2(path, n_points=None):
    import zlib
    b = open(path, "rb").read()
    v, n = struct.unpack("<II", b[8:16]); header = b[16:16+n].decode(); assert v == 2
    m = re.search(r"points:\[([^\]]*)\]", header)
    grid = np.array([float(x) for x in m.group(1).split(",")]); npts = len(grid)
    off = 16 + n; tables = []
    while off < len(b):
        c, z = struct.unpack("<II", b[off:off+8]); raw = zlib.decompress(b[off+8:off+8+z]); off += 8 + z
        s = c // npts
        scales = np.frombuffer(raw[:4*s], "<f4").astype(float)
        lo = np.frombuffer(raw[4*s:4*s+c], np.uint8).astype(np.uint16)
        hi = np.frombuffer(raw[4*s+c:], np.uint8).astype(np.uint16)
        r = (lo | (hi << 8)).reshape(s, npts)
        q = np.cumsum(r.astype(np.int64), axis=0) & 0xFFFF
        tables.append(((q * scales[:, None] / 65535.0).astype(np.float32)).ravel())
    return header, grid, dict(zip(ORDER, tables))
import sys, numpy as np


H, C, K = 6.62607015e-34, 299792458.0, 1.380649e-23
BANDS = [(3.0, 5.0), (3.4, 4.2), (4.5, 5.0), (3.7, 4.8)]
TEMPS = [260.0, 290.0, 320.0]

def planck_um(lam_um, T):
    lam = lam_um * 1e-6
    return 2*H*C**2/lam**5/np.expm1(H*C/(lam*K*T))*1e-6   # W m-2 sr-1 um-1

def band_planck(lo, hi, T):
    l = np.linspace(lo, hi, 801)
    T = np.atleast_1d(T)[:, None]
    return np.trapezoid(planck_um(l[None, :], T), l, axis=1)

_TABLES = {}
def btemp(lo, hi, L):
    """Inverse band Planck: log-radiance table on a fine T grid, then two Newton steps."""
    if (lo, hi) not in _TABLES:
        T = np.linspace(30.0, 700.0, 6701)
        _TABLES[(lo, hi)] = (T, np.log(np.concatenate([band_planck(lo, hi, T[i:i+500]) for i in range(0, len(T), 500)])))
    T, lg = _TABLES[(lo, hi)]
    L = np.asarray(L, float)
    t = np.interp(np.log(np.maximum(L, 1e-300)), lg, T)
    for _ in range(2):
        v = band_planck(lo, hi, t.ravel()).reshape(t.shape)
        d = (band_planck(lo, hi, t.ravel()+0.01).reshape(t.shape) - v)/0.01
        t = t - (v - L)/d
    return t

def weights(nu, lo, hi):
    """Trapezoid-in-wavelength weights w (len nu) with sum w*y = integral over [lo,hi] um
    of y(lambda), edges closed by linear interpolation in wavenumber."""
    w = np.zeros(len(nu)); nlo, nhi = 1e4/hi, 1e4/lo
    inside = [i for i in range(len(nu)) if nlo < nu[i] < nhi]
    # points: (lambda, coefficient vector)
    pts = []
    def edge(nv):
        j = np.searchsorted(nu, nv); j = min(max(j, 1), len(nu)-1)
        f = (nv - nu[j-1])/(nu[j]-nu[j-1]); c = np.zeros(len(nu)); c[j-1] = 1-f; c[j] = f
        return c
    pts.append((lo, edge(nhi)))
    for i in sorted(inside, key=lambda i: -nu[i]):
        c = np.zeros(len(nu)); c[i] = 1; pts.append((1e4/nu[i], c))
    pts.append((hi, edge(nlo)))
    for (l0, c0), (l1, c1) in zip(pts, pts[1:]):
        w += 0.5*(l1-l0)*(c0+c1)
    return w

def evaluate(nu, tabs, ref=None):
    """Per band: (slant apparent T [paths x temps], sky BT [paths])."""
    out = {}
    n = len(nu)
    tau = np.concatenate([tabs["slant_transmission"], tabs["level_transmission"], tabs["cor_transmission"]]).reshape(-1, n).astype(float)
    lp_slant = np.concatenate([tabs["slant_path_radiance"], tabs["level_path_radiance"]]).reshape(-1, n).astype(float)
    ncor = tabs["cor_transmission"].size // n
    sky = np.concatenate([tabs["slant_sky_radiance"], tabs["sky_radiance"], tabs["sky_hemispheric"]]).reshape(-1, n).astype(float)
    per_um = nu**2/1e4
    for lo, hi in BANDS:
        w = weights(nu, lo, hi)
        tbar = tau[:tau.shape[0]-ncor] @ w / (hi-lo)
        lp = (lp_slant*per_um) @ w
        ls = (sky*per_um) @ w
        lb = band_planck(lo, hi, np.array(TEMPS))
        app = btemp(lo, hi, tbar[:, None]*lb[None, :] + lp[:, None])
        out[(lo, hi)] = (app, btemp(lo, hi, ls), tau[tau.shape[0]-ncor:] @ w / (hi-lo))
    return out

def quant_tau(t):
    return np.round(np.clip(t, 0, 1)*65535)/65535

def quant_lin(x, n, bits=16):
    s = x.reshape(-1, n); m = s.max(axis=1, keepdims=True); m[m == 0] = 1
    q = (1 << bits) - 1
    return (np.round(s/m*q)/q*m).ravel()

def quant_f16(x, n):
    s = x.reshape(-1, n).astype(float); m = s.max(axis=1, keepdims=True); m[m == 0] = 1
    return ((s/m).astype(np.float16).astype(float)*m).ravel()

def quant_log(x, n):
    s = x.reshape(-1, n).astype(float); pos = np.where(s > 0, s, np.nan)
    lo = np.nanmin(np.log(pos), axis=1, keepdims=True); hi = np.nanmax(np.log(pos), axis=1, keepdims=True)
    span = np.where(hi > lo, hi-lo, 1.0)
    q = np.where(s > 0, np.round((np.log(np.where(s > 0, s, 1))-lo)/span*65534)+1, 0)
    return np.where(q > 0, np.exp(lo + (q-1)/65534*span), 0.0).ravel()

RAD = ["level_path_radiance", "sky_radiance", "sky_hemispheric", "slant_path_radiance", "slant_sky_radiance"]

def smooth(s, k):
    """Triangular filter of half-width k samples (weights k-|j|, normalised), so that the
    trapezoid on every k-th sample keeps the integral; renormalised at the ends."""
    if k == 1:
        return s
    w = np.array([k - abs(j) for j in range(-k+1, k)], float)
    num = np.zeros_like(s); den = np.zeros(s.shape[1])
    n = s.shape[1]
    for j, wj in zip(range(-k+1, k), w):
        lo, hi = max(0, -j), min(n, n-j)
        num[:, lo:hi] += wj*s[:, lo+j:hi+j]; den[lo:hi] += wj
    return num/den

def candidate(nu, tabs, step, enc, filt=False, lo_nu=2000.0, hi_nu=3340.0):
    k = step // 5
    i0 = int(np.searchsorted(nu, lo_nu)); i1 = int(np.searchsorted(nu, hi_nu))
    sel = np.arange(i0, i1+1, k)
    n = len(nu); m = len(sel)
    out = {}
    for key, a in tabs.items():
        full = a.reshape(-1, n).astype(np.float64)
        if filt:
            full = smooth(full, k)
        s = full[:, sel].ravel()
        if enc == "f32":
            s = s.astype(np.float32).astype(float)
        elif key in RAD:
            s = {"u16": lambda x: quant_lin(x, m), "f16": lambda x: quant_f16(x, m), "log16": lambda x: quant_log(x, m)}[enc](s)
        else:
            s = quant_tau(s)
        out[key] = s
    count = sum(a.size for a in tabs.values()) // n
    nrad = sum(tabs[k].size for k in RAD) // n
    bpp = 4 if enc == "f32" else 2
    nbytes = count*m*bpp + (0 if enc == "f32" else nrad*4 + (nrad*4 if enc == "log16" else 0))
    return nu[sel], out, nbytes

CANDS = [(5, "f32", False), (10, "f32", False), (20, "f32", False), (5, "u16", False), (10, "u16", False),
         (10, "f16", False), (10, "log16", False), (20, "u16", False),
         (10, "f32", True), (20, "f32", True), (10, "u16", True), (20, "u16", True), (10, "f16", True)]
if len(sys.argv) > 1 and sys.argv[1] == "--quick":
    sys.argv.pop(1)
    CANDS = [c for c in CANDS if c[2] or c[0] == 5]

def main():
    for path in sys.argv[1:]:
        header, nu, tabs = read(path)
        ref = evaluate(nu, {k: v.astype(float) for k, v in tabs.items()})
        print(path, "grid", nu[0], nu[-1], len(nu))
        import os
        v2 = path.replace("-full.bin", ".bin")
        if os.path.exists(v2):
            _, g2, t2 = read_v2(v2)
            got = evaluate(g2, {k: v.astype(float) for k, v in t2.items()})
            parts = []
            for b in BANDS:
                ea = np.abs(got[b][0]-ref[b][0]); es = np.abs(got[b][1]-ref[b][1])
                parts.append(f"{b[0]}-{b[1]}: path {ea.max():.4f} sky {es.max():.4f}")
            print(f"  CHOSEN v2 file {os.path.getsize(v2)/1e6:6.3f} MB | " + " | ".join(parts), flush=True)
        for step, enc, filt in CANDS:
            cn, ct, nbytes = candidate(nu, tabs, step, enc, filt)
            got = evaluate(cn, ct)
            parts = []
            for b in BANDS:
                ea = np.abs(got[b][0]-ref[b][0]); es = np.abs(got[b][1]-ref[b][1])
                ec = np.abs(got[b][2]-ref[b][2])
                parts.append(f"{b[0]}-{b[1]}: path {ea.max():.4f} sky {es.max():.4f}")
            print(f"  {step:2d} cm-1 {'tri' if filt else 'dec'} {enc:5s} {(nbytes+len(header))/1e6:6.2f} MB | " + " | ".join(parts), flush=True)

main()
