//! A cluster: contiguous rods whose contacts are being integrated with the fixed-step
//! Strang splitting (half kick of contact forces, exact free flight, half kick).
//!
//! The cluster lives on the global grid t = k h with h a power of two, which makes
//! episodes of different clusters with equal h synchronous and the whole scheme
//! time-reversible. Between steps the momenta lag by half a kick ("not fresh");
//! `sync` completes it, so kick(h/2)+kick(h/2) replaces the merged kick(h).

use super::rod::Rod;

/// Ring geometry and contact law shared by all clusters.
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct Geom {
    pub n: usize,
    pub alpha: f64,
    pub b: f64,
    pub perimeter: f64,
    /// Deactivation threshold on z = α r.
    pub z_off: f64,
}

impl Geom {
    /// Gap r_k of contact k (rod k, rod k+1) from the rods' centres and end
    /// displacements `ur` (right end of rod k) and `ul` (left end of rod k+1).
    pub fn gap(&self, rods: &[Rod], k: usize, ur: f64, ul: f64) -> f64 {
        let kn = (k + 1) % self.n;
        let shift = if kn == 0 { self.perimeter } else { 0.0 };
        let (a, b) = (&rods[k], &rods[kn]);
        b.x + shift - a.x - 0.5 * (a.len + b.len) + ul - ur
    }

    /// Contact force F = α B e^{−α r} and its z = α r.
    pub fn force(&self, r: f64) -> (f64, f64) {
        let z = self.alpha * r;
        (self.alpha * self.b * (-z).exp(), z)
    }
}

/// Rods in contact, integrated together.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub(crate) struct Cluster {
    /// Member rods in ring order; member m+1 is rod rods[m]+1 (mod N).
    pub rods: Vec<usize>,
    /// Closed ring: the contact from the last member to the first is internal too.
    pub ring: bool,
    /// Grid index: the cluster time is k h.
    pub k: i64,
    pub h: f64,
    cs: Vec<Vec<f64>>,
    sn: Vec<Vec<f64>>,
    /// Per internal contact j (member j, member j+1): force and z at the cluster time.
    pub force: Vec<f64>,
    pub z: Vec<f64>,
    /// Per member: (u_left, u_right) at the cluster time.
    ends: Vec<(f64, f64)>,
    /// True when momenta are synchronized with positions (no pending half kick).
    pub fresh: bool,
    /// Total (lab-frame) energy when the membership was last set; conserved.
    pub energy: f64,
    /// Per internal contact: (activation time, relative velocity at activation,
    /// ∫ (Ṙ_{k+1} − Ṙ_k)² dt so far, with mid-step velocities).
    pub start: Vec<(f64, f64, f64)>,
    /// Number of fine steps taken (cost accounting).
    pub steps: u64,
}

impl Cluster {
    /// New synchronized cluster at grid index `k` with step `h` (rods already at k h).
    pub fn new(
        rods: Vec<usize>,
        ring: bool,
        k: i64,
        h: f64,
        start: Vec<(f64, f64, f64)>,
        all: &[Rod],
        g: &Geom,
    ) -> Cluster {
        let len = rods.len();
        let mut c = Cluster {
            rods,
            ring,
            k,
            h,
            cs: Vec::new(),
            sn: Vec::new(),
            force: Vec::new(),
            z: Vec::new(),
            ends: vec![(0.0, 0.0); len],
            fresh: true,
            energy: 0.0,
            start,
            steps: 0,
        };
        c.set_step(h, all);
        c.refresh(all, g);
        c
    }

    pub fn time(&self) -> f64 {
        self.k as f64 * self.h
    }

    /// Number of internal contacts.
    pub fn n_int(&self) -> usize {
        if self.ring {
            self.rods.len()
        } else {
            self.rods.len() - 1
        }
    }

    /// Global index of internal contact j (its left rod).
    pub fn contact(&self, j: usize) -> usize {
        self.rods[j]
    }

    /// Changes the step (a power of two); the grid index is rescaled so the time is kept.
    pub fn set_step(&mut self, h: f64, all: &[Rod]) {
        let t = self.time();
        self.h = h;
        self.k = (t / h).round() as i64;
        self.cs.clear();
        self.sn.clear();
        for &i in &self.rods {
            let (s, c): (Vec<f64>, Vec<f64>) =
                all[i].omega.iter().map(|w| (w * h).sin_cos()).unzip();
            self.cs.push(c);
            self.sn.push(s);
        }
    }

    /// Recomputes end displacements, forces and the cluster energy from the rods.
    pub fn refresh(&mut self, all: &[Rod], g: &Geom) {
        self.ends = self.rods.iter().map(|&i| all[i].ends()).collect();
        self.compute_forces(all, g);
        let pot: f64 = self.force.iter().map(|f| f / g.alpha).sum();
        self.energy = self.rods.iter().map(|&i| all[i].energy()).sum::<f64>() + pot;
    }

    fn compute_forces(&mut self, all: &[Rod], g: &Geom) -> bool {
        let (len, n_int) = (self.rods.len(), self.n_int());
        self.force.resize(n_int, 0.0);
        self.z.resize(n_int, 0.0);
        let mut any_off = false;
        for j in 0..n_int {
            let r = g.gap(
                all,
                self.rods[j],
                self.ends[j].1,
                self.ends[(j + 1) % len].0,
            );
            let (f, z) = g.force(r);
            self.force[j] = f;
            self.z[j] = z;
            any_off |= z > g.z_off;
        }
        any_off
    }

    /// Forces (left end, right end) on member m.
    pub fn member_forces(&self, m: usize) -> (f64, f64) {
        let n_int = self.n_int();
        let fl = if m > 0 {
            self.force[m - 1]
        } else if self.ring {
            self.force[n_int - 1]
        } else {
            0.0
        };
        let fr = if m < n_int { self.force[m] } else { 0.0 };
        (fl, fr)
    }

    fn kick_all(&self, all: &mut [Rod], dt: f64) {
        for (m, &i) in self.rods.iter().enumerate() {
            let (fl, fr) = self.member_forces(m);
            all[i].kick(dt, fl, fr);
        }
    }

    /// One Strang step (kick, exact drift, forces); the closing half kick is left
    /// pending. Returns true if some internal contact is now beyond `z_off`.
    pub fn step(&mut self, all: &mut [Rod], g: &Geom) -> bool {
        let dt = if self.fresh { 0.5 * self.h } else { self.h };
        self.fresh = false;
        self.k += 1;
        let t = self.time();
        for (m, &i) in self.rods.iter().enumerate() {
            let (fl, fr) = self.member_forces(m);
            self.ends[m] = all[i].kick_drift(dt, fl, fr, self.h, &self.cs[m], &self.sn[m]);
            all[i].t = t;
        }
        // Mid-step (kicked, not yet re-kicked) velocities: drift leaves them unchanged.
        let len = self.rods.len();
        for j in 0..self.n_int() {
            let dv = all[self.rods[(j + 1) % len]].v - all[self.rods[j]].v;
            self.start[j].2 += self.h * dv * dv;
        }
        self.steps += 1;
        self.compute_forces(all, g)
    }

    /// Completes the pending half kick.
    pub fn sync(&mut self, all: &mut [Rod]) {
        if !self.fresh {
            self.kick_all(all, 0.5 * self.h);
            self.fresh = true;
        }
    }

    /// Copies of the member rods with the pending half kick applied (for read-only
    /// observables that must not perturb the trajectory).
    pub fn synced_copies(&self, all: &[Rod]) -> Vec<Rod> {
        self.rods
            .iter()
            .enumerate()
            .map(|(m, &i)| {
                let mut r = all[i].clone();
                if !self.fresh {
                    let (fl, fr) = self.member_forces(m);
                    r.kick(0.5 * self.h, fl, fr);
                }
                r
            })
            .collect()
    }

    /// Potential energy of the internal contacts, B e^{−z} = F/α.
    pub fn potential(&self, g: &Geom) -> f64 {
        self.force.iter().map(|f| f / g.alpha).sum()
    }
}
