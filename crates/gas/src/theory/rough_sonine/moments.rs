//! The closed forms of the collisional moments of the first Sonine approximation
//! (`super`'s documentation): the exact Gaussian averages of polynomials, derived with
//! computer algebra by `scripts/rough-sonine.py` (which prints these two tables), checked
//! against Monte Carlo averages of the collision rule `restitution::rough::collide`
//! (`super::monte_carlo`).
//!
//! Variables: a = alpha, e = eta = q (1 + beta) / (2 (1 + q)), r = eta / q, t = theta =
//! T_rot / T_tr, ti = 1 / theta; a2 = a^2 and so on. Row m, column k: the collisional
//! moment N_k[m] (module `super`), rows in the order of [`super::Moment`], columns in the
//! order of [`super::Weight`].

/// The table of `super::CollisionalMoments` for spheres (`dimension` 3: d_t = d_r = 3)
/// or disks (2: d_t = 2, d_r = 1).
pub(super) fn table(dimension: usize, a: f64, e: f64, r: f64, t: f64) -> [[f64; 4]; 6] {
    let ti = 1.0 / t;
    let (a2, a4) = (a * a, a * a * a * a);
    let (e2, e3, e4) = (e * e, e * e * e, e * e * e * e);
    let (r2, r3, r4) = (r * r, r * r * r, r * r * r * r);
    if dimension == 2 {
        disks(a, a2, a4, e, e2, e3, e4, r, r2, r3, r4, t, ti)
    } else {
        spheres(a, a2, a4, e, e2, e3, e4, r, r2, r3, r4, t, ti)
    }
}

#[allow(clippy::too_many_arguments)]
#[rustfmt::skip]
fn spheres(
    a: f64, a2: f64, a4: f64, e: f64, e2: f64, e3: f64, e4: f64,
    r: f64, r2: f64, r3: f64, r4: f64, t: f64, ti: f64,
) -> [[f64; 4]; 6] {
    [
        // collisions (2: both particles)
        [
            // Maxwellian
            (2.0),
            // a20
            (-1.0 / 8.0),
            // a02
            0.0,
            // a11
            0.0,
        ],
        // Delta(c1^2 + c2^2)
        [
            // Maxwellian
            (-1.0 - 4.0 * e + 4.0 * e2 + a2)
            + t * (4.0 * e * r),
            // a20
            (-3.0 / 16.0 - 3.0 / 4.0 * e + 3.0 / 4.0 * e2 + 3.0 / 16.0 * a2)
            + t * (-1.0 / 4.0 * e * r),
            // a02
            0.0,
            // a11
            t * (e * r),
        ],
        // Delta(w1^2 + w2^2)
        [
            // Maxwellian
            ti * (4.0 * e * r)
            + (-4.0 * r + 4.0 * r2),
            // a20
            ti * (3.0 / 4.0 * e * r)
            + (1.0 / 4.0 * r - 1.0 / 4.0 * r2),
            // a02
            0.0,
            // a11
            (-r + r2),
        ],
        // Delta(c1^4 + c2^4)
        [
            // Maxwellian
            (-9.0 / 2.0 - 18.0 * e + 34.0 * e2 - 32.0 * e3 + 16.0 * e4 + 7.0 / 2.0 * a2
                - 4.0 * a2 * e + 4.0 * a2 * e2 + a4)
            + t * (18.0 * e * r - 32.0 * e2 * r + 32.0 * e3 * r + 4.0 * a2 * e * r)
            + t * t * (16.0 * e2 * r2),
            // a20
            (-271.0 / 32.0 - 207.0 / 8.0 * e + 327.0 / 8.0 * e2 - 30.0 * e3 + 15.0 * e4
                - 2.0 * a + 4.0 * a * e + 177.0 / 32.0 * a2 - 15.0 / 4.0 * a2 * e
                + 15.0 / 4.0 * a2 * e2 + 15.0 / 16.0 * a4)
            + t * (35.0 / 8.0 * e * r - 6.0 * e2 * r + 6.0 * e3 * r + 3.0 / 4.0 * a2 * e * r)
            + t * t * (-e2 * r2),
            // a02
            t * t * (8.0 * e2 * r2),
            // a11
            t * (27.0 / 2.0 * e * r - 24.0 * e2 * r + 24.0 * e3 * r + 3.0 * a2 * e * r)
            + t * t * (8.0 * e2 * r2),
        ],
        // Delta(w1^4 + w2^4)
        [
            // Maxwellian
            ti * ti * (16.0 * e2 * r2)
            + ti * (20.0 * e * r - 32.0 * e * r2 + 32.0 * e * r3)
            + (-20.0 * r + 36.0 * r2 - 32.0 * r3 + 16.0 * r4),
            // a20
            ti * ti * (15.0 * e2 * r2)
            + ti * (15.0 / 4.0 * e * r - 6.0 * e * r2 + 6.0 * e * r3)
            + (5.0 / 4.0 * r - 9.0 / 4.0 * r2 + 2.0 * r3 - r4),
            // a02
            (-20.0 * r + 26.0 * r2 - 16.0 * r3 + 8.0 * r4),
            // a11
            ti * (15.0 * e * r - 24.0 * e * r2 + 24.0 * e * r3)
            + (-10.0 * r + 18.0 * r2 - 16.0 * r3 + 8.0 * r4),
        ],
        // Delta(c1^2 w1^2 + c2^2 w2^2)
        [
            // Maxwellian
            ti * (7.0 * e * r - 16.0 * e2 * r + 16.0 * e3 * r + 2.0 * a2 * e * r)
            + (-3.0 / 2.0 - 5.0 * r + 5.0 * r2 - 6.0 * e + 12.0 * e * r - 16.0 * e * r2
                + 6.0 * e2 - 16.0 * e2 * r + 32.0 * e2 * r2 + 3.0 / 2.0 * a2 - 2.0 * a2 * r
                + 2.0 * a2 * r2)
            + t * (8.0 * e * r - 16.0 * e * r2 + 16.0 * e * r3),
            // a20
            ti * (129.0 / 16.0 * e * r - 15.0 * e2 * r + 15.0 * e3 * r
                + 15.0 / 8.0 * a2 * e * r)
            + (-9.0 / 32.0 - 23.0 / 16.0 * r + 23.0 / 16.0 * r2 - 9.0 / 8.0 * e
                + 9.0 / 4.0 * e * r - 3.0 * e * r2 + 9.0 / 8.0 * e2 - 3.0 * e2 * r
                + 6.0 * e2 * r2 + 9.0 / 32.0 * a2 - 3.0 / 8.0 * a2 * r + 3.0 / 8.0 * a2 * r2)
            + t * (-1.0 / 2.0 * e * r + e * r2 - e * r3),
            // a02
            t * (5.0 * e * r - 8.0 * e * r2 + 8.0 * e * r3),
            // a11
            (-21.0 / 8.0 - 23.0 / 4.0 * r + 15.0 / 4.0 * r2 - 15.0 / 2.0 * e + 15.0 * e * r
                - 12.0 * e * r2 + 9.0 / 2.0 * e2 - 12.0 * e2 * r + 24.0 * e2 * r2
                - 3.0 / 2.0 * a + 2.0 * a * r + 9.0 / 8.0 * a2 - 3.0 / 2.0 * a2 * r
                + 3.0 / 2.0 * a2 * r2)
            + t * (4.0 * e * r - 8.0 * e * r2 + 8.0 * e * r3),
        ],
    ]
}

#[allow(clippy::too_many_arguments)]
#[rustfmt::skip]
fn disks(
    a: f64, a2: f64, a4: f64, e: f64, e2: f64, e3: f64, e4: f64,
    r: f64, r2: f64, r3: f64, r4: f64, t: f64, ti: f64,
) -> [[f64; 4]; 6] {
    [
        // collisions (2: both particles)
        [
            // Maxwellian
            (2.0),
            // a20
            (-1.0 / 8.0),
            // a02
            0.0,
            // a11
            0.0,
        ],
        // Delta(c1^2 + c2^2)
        [
            // Maxwellian
            (-1.0 - 2.0 * e + 2.0 * e2 + a2)
            + t * (2.0 * e * r),
            // a20
            (-3.0 / 16.0 - 3.0 / 8.0 * e + 3.0 / 8.0 * e2 + 3.0 / 16.0 * a2)
            + t * (-1.0 / 8.0 * e * r),
            // a02
            0.0,
            // a11
            t * (1.0 / 2.0 * e * r),
        ],
        // Delta(w1^2 + w2^2)
        [
            // Maxwellian
            ti * (2.0 * e * r)
            + (-2.0 * r + 2.0 * r2),
            // a20
            ti * (3.0 / 8.0 * e * r)
            + (1.0 / 8.0 * r - 1.0 / 8.0 * r2),
            // a02
            0.0,
            // a11
            (-1.0 / 2.0 * r + 1.0 / 2.0 * r2),
        ],
        // Delta(c1^4 + c2^4)
        [
            // Maxwellian
            (-7.0 / 2.0 - 7.0 * e + 13.0 * e2 - 12.0 * e3 + 6.0 * e4 + 5.0 / 2.0 * a2
                - 2.0 * a2 * e + 2.0 * a2 * e2 + a4)
            + t * (7.0 * e * r - 12.0 * e2 * r + 12.0 * e3 * r + 2.0 * a2 * e * r)
            + t * t * (6.0 * e2 * r2),
            // a20
            (-209.0 / 32.0 - 161.0 / 16.0 * e + 251.0 / 16.0 * e2 - 45.0 / 4.0 * e3
                + 45.0 / 8.0 * e4 - a + 2.0 * a * e + 147.0 / 32.0 * a2 - 15.0 / 8.0 * a2 * e
                + 15.0 / 8.0 * a2 * e2 + 15.0 / 16.0 * a4)
            + t * (29.0 / 16.0 * e * r - 9.0 / 4.0 * e2 * r + 9.0 / 4.0 * e3 * r
                + 3.0 / 8.0 * a2 * e * r)
            + t * t * (-3.0 / 8.0 * e2 * r2),
            // a02
            t * t * (3.0 * e2 * r2),
            // a11
            t * (21.0 / 4.0 * e * r - 9.0 * e2 * r + 9.0 * e3 * r + 3.0 / 2.0 * a2 * e * r)
            + t * t * (3.0 * e2 * r2),
        ],
        // Delta(w1^4 + w2^4)
        [
            // Maxwellian
            ti * ti * (6.0 * e2 * r2)
            + ti * (6.0 * e * r - 12.0 * e * r2 + 12.0 * e * r3)
            + (-6.0 * r + 12.0 * r2 - 12.0 * r3 + 6.0 * r4),
            // a20
            ti * ti * (45.0 / 8.0 * e2 * r2)
            + ti * (9.0 / 8.0 * e * r - 9.0 / 4.0 * e * r2 + 9.0 / 4.0 * e * r3)
            + (3.0 / 8.0 * r - 3.0 / 4.0 * r2 + 3.0 / 4.0 * r3 - 3.0 / 8.0 * r4),
            // a02
            (-6.0 * r + 9.0 * r2 - 6.0 * r3 + 3.0 * r4),
            // a11
            ti * (9.0 / 2.0 * e * r - 9.0 * e * r2 + 9.0 * e * r3)
            + (-3.0 * r + 6.0 * r2 - 6.0 * r3 + 3.0 * r4),
        ],
        // Delta(c1^2 w1^2 + c2^2 w2^2)
        [
            // Maxwellian
            ti * (5.0 / 2.0 * e * r - 6.0 * e2 * r + 6.0 * e3 * r + a2 * e * r)
            + (-1.0 / 2.0 - 3.0 / 2.0 * r + 3.0 / 2.0 * r2 - e + 4.0 * e * r - 6.0 * e * r2 + e2
                - 6.0 * e2 * r + 12.0 * e2 * r2 + 1.0 / 2.0 * a2 - a2 * r + a2 * r2)
            + t * (2.0 * e * r - 6.0 * e * r2 + 6.0 * e * r3),
            // a20
            ti * (99.0 / 32.0 * e * r - 45.0 / 8.0 * e2 * r + 45.0 / 8.0 * e3 * r
                + 15.0 / 16.0 * a2 * e * r)
            + (-3.0 / 32.0 - 17.0 / 32.0 * r + 17.0 / 32.0 * r2 - 3.0 / 16.0 * e
                + 3.0 / 4.0 * e * r - 9.0 / 8.0 * e * r2 + 3.0 / 16.0 * e2 - 9.0 / 8.0 * e2 * r
                + 9.0 / 4.0 * e2 * r2 + 3.0 / 32.0 * a2 - 3.0 / 16.0 * a2 * r
                + 3.0 / 16.0 * a2 * r2)
            + t * (-1.0 / 8.0 * e * r + 3.0 / 8.0 * e * r2 - 3.0 / 8.0 * e * r3),
            // a02
            t * (3.0 / 2.0 * e * r - 3.0 * e * r2 + 3.0 * e * r3),
            // a11
            (-7.0 / 8.0 - 13.0 / 8.0 * r + 9.0 / 8.0 * r2 - 5.0 / 4.0 * e + 5.0 * e * r
                - 9.0 / 2.0 * e * r2 + 3.0 / 4.0 * e2 - 9.0 / 2.0 * e2 * r + 9.0 * e2 * r2
                - 1.0 / 2.0 * a + a * r + 3.0 / 8.0 * a2 - 3.0 / 4.0 * a2 * r
                + 3.0 / 4.0 * a2 * r2)
            + t * (e * r - 3.0 * e * r2 + 3.0 * e * r3),
        ],
    ]
}
