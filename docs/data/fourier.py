"""Fourier's law from a run of docs/data/fourier-3d.toml (docs/walls.md): the heat flux from
walls.csv, the temperature gradient from profiles.csv, the conductivity against Enskog's.

Usage: python3 docs/data/fourier.py OUT [START]  (OUT: the run's output directory; START:
the collisions per particle from which the state is steady, default 1500)."""
import csv, math, collections, sys
out = sys.argv[1]
start = float(sys.argv[2]) if len(sys.argv) > 2 else 1500
rows = [r for r in csv.DictReader(open(out + '/profiles.csv')) if float(r['collisions_per_particle']) >= start]
times = sorted(set(float(r['time']) for r in rows))
n = collections.defaultdict(list); T = collections.defaultdict(list)
for r in rows:
    z = float(r['position']); n[z].append(float(r['density'])); T[z].append(float(r['temperature']))
zs = sorted(n)
nm = [sum(n[z])/len(n[z]) for z in zs]; Tm = [sum(T[z])/len(T[z]) for z in zs]
w = [r for r in csv.DictReader(open(out + '/walls.csv'))]
def at(side, first):
    sel = [r for r in w if r['side'] == side and float(r['collisions_per_particle']) >= start]
    r = sel[0] if first else sel[-1]
    return float(r['time']), float(r['energy'])
L = (20000 * math.pi / 6 / 0.05) ** (1/3)
A = L * L
t0, e0 = at('low', True); t1, e1 = at('low', False)
s0, f0 = at('high', True); s1, f1 = at('high', False)
q_in = (e1 - e0) / (t1 - t0) / A; q_out = -(f1 - f0) / (s1 - s0) / A
print('L', L, 'window', t0, t1, 'q_in', q_in, 'q_out', q_out)
q = 0.5 * (q_in + q_out)
def kappa_enskog(T, phi, improved):
    chi = (1 - phi/2) / (1 - phi)**3
    k0 = 75/64 * math.sqrt(T/math.pi)
    bn = 4*phi; y = bn*chi
    if improved:
        return k0 * (1.02513 * (1/chi + 1.2*bn + 0.36*bn*bn*chi) + 32/(25*math.pi)*bn*bn*chi)
    return k0 * bn * (1/y + 1.2 + (0.36 + 32/(25*math.pi))*y)
dz = zs[1] - zs[0]
print(' z      n       T      phi    kappa_meas  Enskog1  Enskog+  ratio1  ratio+')
for i in range(1, len(zs)-1):
    grad = (Tm[i+1] - Tm[i-1]) / (2*dz)
    phi = nm[i] * math.pi / 6
    km = q / -grad
    k1 = kappa_enskog(Tm[i], phi, False); k2 = kappa_enskog(Tm[i], phi, True)
    print('%5.1f %.5f %.4f %.4f %.4f %.4f %.4f %.4f %.4f' % (zs[i], nm[i], Tm[i], phi, km, k1, k2, km/k1, km/k2))
print('wall T: low 1.5 vs first slab', Tm[0], ' high 0.5 vs last', Tm[-1])
# Bulk: slabs more than 3 mean free paths (~7 diameters) from the walls.
bulk = [i for i in range(1, len(zs)-1) if 7 <= zs[i] <= L - 7]
def stats(improved):
    rs = []
    for i in bulk:
        grad = (Tm[i+1] - Tm[i-1]) / (2*dz)
        rs.append(q / -grad / kappa_enskog(Tm[i], nm[i]*math.pi/6, improved))
    m = sum(rs)/len(rs); s = (sum((x-m)**2 for x in rs)/(len(rs)-1)/len(rs))**0.5
    return m, s
# Integral form: the temperature drop across the bulk predicted by q and kappa(z).
a, b = bulk[0], bulk[-1]
pred = sum(q / kappa_enskog(Tm[i], nm[i]*math.pi/6, True) * dz for i in range(a, b)) 
print('bulk slabs', len(bulk), 'mean ratio first Sonine %.4f +- %.4f' % stats(False), ' with 1.02513 %.4f +- %.4f' % stats(True))
print('temperature drop across the bulk: measured %.4f, from q and Enskog (1.02513) %.4f' % (Tm[a]-Tm[b], pred))
