//! Tests of the `material` module: contact parameters, units and validation.

use approx::assert_relative_eq;
use restitution::material::{
    builtin_materials, dissipative_constant_from_viscosities, material_by_name, speed_from_vstar,
    vstar, ContactPair, Material, Sphere, UnitSystem, ICE_BRIDGES_BETA_CGS,
};
use restitution::Error;

/// Glass-like test material with round numbers: Y = 70 GPa, ν = 0.25, 2500 kg/m³, A = 1 ns.
fn test_glass() -> Material {
    Material::new("test-glass", 7.0e10, 0.25, 2500.0, Some(1.0e-9), "test").unwrap()
}

/// Two identical test-glass spheres of radius 1 mm.
fn glass_pair() -> ContactPair {
    let material = test_glass();
    let sphere = Sphere::from_density(1.0e-3, material.density).unwrap();
    ContactPair::new(&material, sphere, sphere).unwrap()
}

fn error_names(error: &Error, field: &str) -> bool {
    matches!(error, Error::OutOfRange { name, .. } if name == field)
}

#[test]
fn sphere_mass_from_density() {
    // m = 4/3 π (1e-3)³ 2500 = 1.0471975511965977e-5 kg
    let sphere = Sphere::from_density(1.0e-3, 2500.0).unwrap();
    assert_relative_eq!(
        sphere.mass,
        1.047_197_551_196_597_7e-5,
        max_relative = 1e-14
    );
    assert_eq!(sphere.radius, 1.0e-3);
}

#[test]
fn effective_mass_and_radius_of_identical_spheres() {
    let pair = glass_pair();
    assert_relative_eq!(
        pair.effective_mass(),
        5.235_987_755_982_989e-6,
        max_relative = 1e-14
    );
    assert_relative_eq!(pair.effective_radius(), 5.0e-4, max_relative = 1e-15);
}

#[test]
fn effective_mass_and_radius_of_different_spheres() {
    let pair = ContactPair::new(
        &test_glass(),
        Sphere::new(1.0, 2.0).unwrap(),
        Sphere::new(3.0, 6.0).unwrap(),
    )
    .unwrap();
    assert_relative_eq!(pair.effective_mass(), 1.5, max_relative = 1e-15);
    assert_relative_eq!(pair.effective_radius(), 0.75, max_relative = 1e-15);
}

#[test]
fn elastic_constant_k_gamma_beta_by_hand() {
    let pair = glass_pair();
    // ρ = 2·7e10·√(5e-4) / (3·(1 − 0.0625)) = 1.4e11 · 0.0223606797749979 / 2.8125
    let rho = 1.4e11 * 0.022_360_679_774_997_9 / 2.8125;
    assert_relative_eq!(pair.elastic_constant(), rho, max_relative = 1e-14);
    assert_relative_eq!(
        pair.elastic_constant(),
        1.113_064_948_799_895_3e9,
        max_relative = 1e-13
    );
    // k = ρ / m_eff
    assert_relative_eq!(pair.k(), 2.125_797_463_005_968_8e14, max_relative = 1e-13);
    // γ = 1.5 ρ A / m_eff
    assert_relative_eq!(
        pair.gamma().unwrap(),
        3.188_696_194_508_953_5e5,
        max_relative = 1e-13
    );
    // β = 1.5 A k^(2/5)
    assert_relative_eq!(
        pair.beta().unwrap(),
        8.074_209_482_230_836e-4,
        max_relative = 1e-13
    );
}

#[test]
fn beta_equals_gamma_times_k_to_minus_three_fifths() {
    let pair = glass_pair();
    let from_sp2008 = pair.gamma().unwrap() * pair.k().powf(-0.6);
    assert_relative_eq!(pair.beta().unwrap(), from_sp2008, max_relative = 1e-13);
}

#[test]
fn beta_in_cgs() {
    let pair = glass_pair();
    let beta_si = pair.beta().unwrap();
    assert_eq!(pair.beta_in(UnitSystem::Si).unwrap(), beta_si);
    assert_relative_eq!(
        pair.beta_in(UnitSystem::Cgs).unwrap(),
        beta_si / 100f64.powf(0.2),
        max_relative = 1e-14
    );
}

#[test]
fn pair_vstar_round_trip() {
    let pair = glass_pair();
    for v in [1e-4, 0.01, 1.0, 37.0] {
        let scaled = pair.vstar(v).unwrap();
        assert_relative_eq!(
            pair.speed_from_vstar(scaled).unwrap(),
            v,
            max_relative = 1e-12
        );
    }
}

#[test]
fn scales_of_mp2011() {
    let pair = glass_pair();
    let v = 2.0;
    let k = pair.k();
    assert_relative_eq!(
        pair.time_scale(v).unwrap(),
        k.powf(-0.4) * v.powf(-0.2),
        max_relative = 1e-14
    );
    assert_relative_eq!(
        pair.length_scale(v).unwrap(),
        k.powf(-0.4) * v.powf(0.8),
        max_relative = 1e-14
    );
    // length / time = v exactly: the scaled initial speed is 1.
    let ratio = pair.length_scale(v).unwrap() / pair.time_scale(v).unwrap();
    assert_relative_eq!(ratio, v, max_relative = 1e-14);
    assert!(pair.time_scale(0.0).is_err());
}

#[test]
fn missing_dissipative_constant_is_named() {
    let material = material_by_name("steel").unwrap();
    let sphere = Sphere::of_material(1e-3, &material).unwrap();
    let pair = ContactPair::new(&material, sphere, sphere).unwrap();
    assert!(pair.elastic_constant() > 0.0);
    for result in [
        pair.gamma(),
        pair.beta(),
        pair.vstar(1.0),
        pair.dissipative_constant(),
    ] {
        let error = result.unwrap_err();
        assert!(error_names(&error, "dissipative_constant"), "{error}");
        assert!(error.to_string().contains("dissipative_constant"));
    }
}

#[test]
fn unit_system_parse_and_display() {
    assert_eq!("si".parse::<UnitSystem>().unwrap(), UnitSystem::Si);
    assert_eq!(" CGS ".parse::<UnitSystem>().unwrap(), UnitSystem::Cgs);
    for units in UnitSystem::ALL {
        assert_eq!(units.to_string().parse::<UnitSystem>().unwrap(), units);
    }
    let message = "mks".parse::<UnitSystem>().unwrap_err().to_string();
    assert!(
        message.contains("unit system") && message.contains("mks"),
        "{message}"
    );
    assert!(
        message.contains("si") && message.contains("cgs"),
        "{message}"
    );
}

#[test]
fn speed_and_length_conversions() {
    assert_relative_eq!(
        UnitSystem::Cgs.speed_from_si(0.025),
        2.5,
        max_relative = 1e-15
    );
    assert_relative_eq!(
        UnitSystem::Cgs.speed_to_si(2.5),
        0.025,
        max_relative = 1e-15
    );
    assert_eq!(UnitSystem::Si.speed_from_si(3.0), 3.0);
    assert_relative_eq!(
        UnitSystem::Cgs.length_from_si(1e-3),
        0.1,
        max_relative = 1e-15
    );
}

#[test]
fn ice_beta_round_trips_between_unit_systems() {
    let beta_si = UnitSystem::Cgs.beta_to_si(ICE_BRIDGES_BETA_CGS);
    // 1.307 (s/cm)^(1/5) = 1.307 · 100^(1/5) (s/m)^(1/5) ≈ 3.283 (s/m)^(1/5)
    assert_relative_eq!(beta_si, 1.307 * 100f64.powf(0.2), max_relative = 1e-14);
    assert_relative_eq!(
        UnitSystem::Cgs.beta_from_si(beta_si),
        ICE_BRIDGES_BETA_CGS,
        max_relative = 1e-14
    );
    assert_eq!(UnitSystem::Si.beta_from_si(beta_si), beta_si);
}

#[test]
fn vstar_is_independent_of_unit_system() {
    let beta_si = UnitSystem::Cgs.beta_to_si(ICE_BRIDGES_BETA_CGS);
    for v_si in [1e-4, 0.025, 1.0, 10.0] {
        let in_si = vstar(beta_si, v_si).unwrap();
        let v_cgs = UnitSystem::Cgs.speed_from_si(v_si);
        let in_cgs = vstar(ICE_BRIDGES_BETA_CGS, v_cgs).unwrap();
        assert_relative_eq!(in_si, in_cgs, max_relative = 1e-14);
    }
}

#[test]
fn ice_speeds_of_mp2011() {
    // v* = 1  ↔  v = 1/β^5 ≈ 0.262 cm/s (MP2011, discussion of Fig. 1)
    let v1 = speed_from_vstar(ICE_BRIDGES_BETA_CGS, 1.0).unwrap();
    assert_relative_eq!(v1, 1.0 / 1.307f64.powi(5), max_relative = 1e-14);
    assert!((v1 - 0.262).abs() < 5e-4, "{v1}");
    // v* = 1.25  ↔  v ≈ 2.44 cm/s ("about 2.5 cm/s" in MP2011)
    let v125 = speed_from_vstar(ICE_BRIDGES_BETA_CGS, 1.25).unwrap();
    assert!((v125 - 2.44).abs() < 5e-3, "{v125}");
    // and back again
    assert_relative_eq!(
        vstar(ICE_BRIDGES_BETA_CGS, v125).unwrap(),
        1.25,
        max_relative = 1e-14
    );
}

#[test]
fn free_vstar_round_trip_and_validation() {
    for scaled in [0.0, 0.3, 1.0, 4.0] {
        let v = speed_from_vstar(0.5, scaled).unwrap();
        assert_relative_eq!(vstar(0.5, v).unwrap(), scaled, max_relative = 1e-14);
    }
    assert!(error_names(&vstar(0.0, 1.0).unwrap_err(), "beta"));
    assert!(error_names(&vstar(-1.0, 1.0).unwrap_err(), "beta"));
    assert!(error_names(&vstar(1.0, -1.0).unwrap_err(), "v"));
    assert!(error_names(&vstar(1.0, f64::INFINITY).unwrap_err(), "v"));
    assert!(error_names(&vstar(f64::NAN, 1.0).unwrap_err(), "beta"));
    assert!(error_names(
        &speed_from_vstar(1.0, f64::NAN).unwrap_err(),
        "vstar"
    ));
}

fn material_error(young: f64, poisson: f64, density: f64, a: Option<f64>) -> Error {
    Material::new("bad", young, poisson, density, a, "test").unwrap_err()
}

#[test]
fn invalid_materials_name_the_field() {
    let poisson_half = material_error(1e9, 0.5, 1000.0, None);
    assert!(error_names(&poisson_half, "poisson_ratio"));
    assert!(
        poisson_half.to_string().contains("(-1, 0.5)"),
        "{poisson_half}"
    );
    assert!(error_names(
        &material_error(1e9, -1.0, 1000.0, None),
        "poisson_ratio"
    ));
    assert!(error_names(
        &material_error(1e9, f64::NAN, 1000.0, None),
        "poisson_ratio"
    ));
    assert!(error_names(
        &material_error(1e9, 0.3, -1.0, None),
        "density"
    ));
    assert!(error_names(
        &material_error(1e9, 0.3, f64::NAN, None),
        "density"
    ));
    assert!(error_names(
        &material_error(0.0, 0.3, 1000.0, None),
        "young_modulus"
    ));
    assert!(error_names(
        &material_error(f64::NAN, 0.3, 1000.0, None),
        "young_modulus"
    ));
    let negative_a = material_error(1e9, 0.3, 1000.0, Some(-1e-9));
    assert!(error_names(&negative_a, "dissipative_constant"));
    assert!(Material::new("ok", 1e9, -0.99, 1000.0, Some(0.0), "test").is_ok());
}

#[test]
fn invalid_spheres_name_the_field() {
    assert!(error_names(&Sphere::new(0.0, 1.0).unwrap_err(), "radius"));
    assert!(error_names(
        &Sphere::new(1.0, f64::NAN).unwrap_err(),
        "mass"
    ));
    assert!(error_names(
        &Sphere::from_density(1.0, -2.0).unwrap_err(),
        "density"
    ));
    let bad = Sphere {
        radius: -1.0,
        mass: 1.0,
    };
    let good = Sphere::new(1.0, 1.0).unwrap();
    assert!(error_names(
        &ContactPair::new(&test_glass(), good, bad).unwrap_err(),
        "radius"
    ));
}

#[test]
fn dissipative_constant_from_viscosities_eq15() {
    // A = (1/3)·(3·2 − 0.5)²/(3·2 + 2·0.5) · (1 − 1/16)(1 − 1/2)/(7e10/16)
    let expected = (1.0 / 3.0) * 30.25 / 7.0 * (0.9375 * 0.5) / (7.0e10 * 0.0625);
    let a = dissipative_constant_from_viscosities(0.5, 2.0, 7.0e10, 0.25).unwrap();
    assert_relative_eq!(a, expected, max_relative = 1e-14);
    assert_relative_eq!(a, 1.543_367_346_938_775_3e-10, max_relative = 1e-13);
}

#[test]
fn dissipative_constant_from_viscosities_validation() {
    let zero_nu = dissipative_constant_from_viscosities(1.0, 1.0, 1e9, 0.0).unwrap_err();
    assert!(error_names(&zero_nu, "poisson_ratio"));
    assert!(zero_nu.to_string().contains("nonzero"), "{zero_nu}");
    let bad_eta = dissipative_constant_from_viscosities(-1.0, 1.0, 1e9, 0.3).unwrap_err();
    assert!(error_names(&bad_eta, "eta1"));
    let bad_young = dissipative_constant_from_viscosities(1.0, 1.0, -1e9, 0.3).unwrap_err();
    assert!(error_names(&bad_young, "young_modulus"));
    assert!(dissipative_constant_from_viscosities(0.0, 0.0, 1e9, 0.3).is_err());
    assert!(dissipative_constant_from_viscosities(1.0, 1.0, 1e9, 0.5).is_err());
}

#[test]
fn builtin_table_is_valid_and_cited() {
    let materials = builtin_materials();
    assert!(materials.len() >= 3);
    for material in &materials {
        material.validate().unwrap();
        assert!(!material.source.is_empty(), "{}", material.name);
        assert_eq!(material_by_name(&material.name).unwrap(), *material);
    }
    for name in ["steel", "soda-lime-glass", "ice"] {
        assert!(materials.iter().any(|m| m.name == name), "{name}");
    }
}

#[test]
fn material_lookup() {
    assert_eq!(
        material_by_name("Soda_Lime Glass").unwrap().name,
        "soda-lime-glass"
    );
    let message = material_by_name("unobtainium").unwrap_err().to_string();
    assert!(message.contains("unobtainium"), "{message}");
    for name in ["steel", "soda-lime-glass", "ice"] {
        assert!(message.contains(name), "{message}");
    }
}

#[test]
fn with_dissipative_constant() {
    let ice = material_by_name("ice").unwrap();
    assert_eq!(ice.dissipative_constant, None);
    let damped = ice.clone().with_dissipative_constant(2e-9).unwrap();
    assert_eq!(damped.dissipative_constant, Some(2e-9));
    assert!(error_names(
        &ice.with_dissipative_constant(f64::NAN).unwrap_err(),
        "dissipative_constant"
    ));
}

// ---- Spheres of unlike materials (MaterialPair) ----

use restitution::material::MaterialPair;
use restitution::{Restitution, Viscoelastic};

#[test]
fn a_pair_of_one_material_is_that_material() {
    let glass = test_glass();
    let a = glass.dissipative_constant.unwrap();
    let triple = (glass.young_modulus, glass.poisson_ratio, a);
    let pair = MaterialPair::new(triple, triple).unwrap();
    let contact = glass_pair();
    let [s, _] = contact.spheres();
    assert_relative_eq!(
        pair.elastic_constant(s.radius, s.radius),
        contact.elastic_constant(),
        max_relative = 1e-14
    );
    assert_relative_eq!(pair.dissipative_constant, a, max_relative = 1e-15);
    assert_relative_eq!(
        pair.beta(s.radius, s.radius, s.mass, s.mass),
        contact.beta().unwrap(),
        max_relative = 1e-14
    );
}

#[test]
fn a_pair_is_symmetric_and_mixes_by_compliance() {
    let (steel, ice) = ((200e9, 0.30, 2e-9), (9.3e9, 0.33, 8e-9));
    let (a, b) = (
        MaterialPair::new(steel, ice).unwrap(),
        MaterialPair::new(ice, steel).unwrap(),
    );
    assert_eq!(a.combined_modulus, b.combined_modulus);
    assert_relative_eq!(
        a.dissipative_constant,
        b.dissipative_constant,
        max_relative = 1e-15
    );
    // The soft ice carries most of the deformation: A_12 lies near ice's A.
    let (d_steel, d_ice) = ((1.0 - 0.09) / 200e9, (1.0 - 0.33f64.powi(2)) / 9.3e9);
    assert_relative_eq!(
        a.dissipative_constant,
        (2e-9 * d_steel + 8e-9 * d_ice) / (d_steel + d_ice),
        max_relative = 1e-14
    );
    assert!(a.dissipative_constant > 7.5e-9);
    assert!(MaterialPair::new((0.0, 0.3, 1.0), ice).is_err());
    assert!(MaterialPair::new(steel, (1.0, 0.5, 1.0)).is_err());
    assert!(MaterialPair::new(steel, (1.0, 0.3, -1.0)).is_err());
}

/// The normal collision of two Kelvin–Voigt bodies of compliances `d` and dissipative
/// constants `a`, in contact as Hertz spheres, integrated without expanding in A: the
/// load-equivalent G = (z_i + A_i ż_i) / D_i is the same in both bodies and z_1 + z_2 =
/// ξ^(3/2) (the correspondence principle behind `MaterialPair`). Units: m_eff = 1 and the
/// prefactor 4 √R_eff / 3 = D_1 + D_2, so that ρ = 1. Returns eps at impact speed `v`
/// (the collision ends when the force vanishes, the improved criterion).
fn two_body_eps(d: [f64; 2], a: [f64; 2], v: f64) -> f64 {
    let prefactor = d[0] + d[1];
    let rate = |s: [f64; 3]| -> [f64; 3] {
        let [xi, xi_dot, z1] = s;
        let root = xi.max(0.0).sqrt();
        let z2 = xi.max(0.0) * root - z1;
        let z1_dot =
            ((z2 + a[1] * 1.5 * root * xi_dot) / d[1] - z1 / d[0]) / (a[0] / d[0] + a[1] / d[1]);
        let force = prefactor * (z1 + a[0] * z1_dot) / d[0];
        [xi_dot, -force, z1_dot]
    };
    let force = |s: [f64; 3]| -(rate(s)[1]);
    // Start just after contact (the neglected impulse is O(t0^(5/2))).
    let (t0, dt) = (1e-7, 2e-5);
    let mut s = [v * t0, v, 0.0];
    loop {
        let k1 = rate(s);
        let step = |k: [f64; 3], h: f64| [s[0] + h * k[0], s[1] + h * k[1], s[2] + h * k[2]];
        let k2 = rate(step(k1, dt / 2.0));
        let k3 = rate(step(k2, dt / 2.0));
        let k4 = rate(step(k3, dt));
        let next: [f64; 3] =
            std::array::from_fn(|i| s[i] + dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
        let (f0, f1) = (force(s), force(next));
        if s[1] < 0.0 && f1 <= 0.0 {
            // The force vanished within the step: interpolate the speed there.
            let w = f0 / (f0 - f1);
            return -(s[1] + w * (next[1] - s[1])) / v;
        }
        s = next;
    }
}

#[test]
fn unlike_materials_collide_as_the_pair_law_to_first_order_in_a() {
    let exact = |beta: f64, v: f64| {
        Viscoelastic::new(beta, "exact".parse().unwrap())
            .unwrap()
            .eps(v)
    };
    // ρ = m_eff = 1: beta = (3/2) A_12.
    let beta_of = |d: [f64; 2], a: [f64; 2]| {
        MaterialPair::new((1.0 / d[0], 0.0, a[0]), (1.0 / d[1], 0.0, a[1]))
            .unwrap()
            .dissipative_constant
            * 1.5
    };
    // The integrator first: one material (A_1 = A_2) is one Kelvin–Voigt body, the law
    // itself, to the integrator's error.
    let (d, v) = ([1.0, 3.0], 1.0);
    let same = two_body_eps(d, [0.05, 0.05], v);
    assert_relative_eq!(same, exact(beta_of(d, [0.05, 0.05]), v), epsilon = 1e-7);
    // Unlike: A_2 = 5 A_1. The pair law is the first order of the expansion in s A, so it
    // must differ from the two-body collision by O(A^2) at most, while 1 - eps is O(A):
    // the difference must fall at least fourfold per halving of A (local order >= 2, less
    // 0.1 for the next order's share). Observed: orders 2.4, 2.45, 2.5 (the O(A^2)
    // term of the energy loss vanishes here).
    let difference = |scale: f64| {
        let a = [scale, 5.0 * scale];
        let two_body = two_body_eps(d, a, v);
        let law = exact(beta_of(d, a), v);
        assert!(1.0 - law > 0.05 * scale, "dissipation is O(A)");
        (two_body - law).abs()
    };
    let differences: Vec<f64> = [0.01, 0.005, 0.0025].map(difference).to_vec();
    for pair in differences.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        assert!(order > 1.9, "order {order} ({differences:?})");
    }
    let dissipation = 1.0 - exact(beta_of(d, [0.0025, 0.0125]), v);
    assert!(differences[2] < 0.01 * dissipation);
}
