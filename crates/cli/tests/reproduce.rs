//! `haff reproduce`: every ID writes its CSV(s) with the right columns, PNG, SVG and a note;
//! `--list` lists every ID; an unknown ID exits 2 naming the argument and the valid IDs.

mod common;

use common::{assert_rejected, haff, stdout_of};

/// Every file stem of `haff reproduce all` and the header of its CSV.
const CSVS: [(&str, &str); 32] = [
    (
        "mp2011-fig1",
        "vstar,exact,pade_1_4,series_5,series_10,series_20,series_40",
    ),
    (
        "mp2011-fig2",
        "vstar,exact,asymptote,paper_power_law,pade_3_6,pade_15_18,pade_best",
    ),
    (
        "mp2011-fig3",
        "vstar,exact,pade_0_3,pade_1_4,pade_2_5,pade_3_6",
    ),
    (
        "mp2011-fig4",
        "v_cm_per_s,vstar,exact,pade_3_6,series_20,series_40",
    ),
    (
        "mp2011-table1",
        "m,n,coefficient,printed,computed,from_table_v,printed_minus_computed",
    ),
    (
        "mp2011-table1-errors",
        "m,n,max_abs_error,at_vstar,max_rel_error,first_positive_pole",
    ),
    (
        "sp2008-fig1",
        "beta_v_1_5,vstar,exact_improved,exact_naive,series_improved_table_v,\
         series_naive_table_iii,series_improved_computed,series_naive_computed",
    ),
    ("sp2008-fig2", "beta5_v,vstar,exact_naive,exact_improved"),
    ("sp2008-fig3", "tau,x,xddot,xdot"),
    (
        "sp2008-table3",
        "i,coefficient,printed,computed,printed_minus_computed,units_of_last_digit",
    ),
    (
        "sp2008-table5",
        "k,printed,computed,printed_minus_computed,units_of_last_digit",
    ),
    (
        "sp2008-dashpot",
        "damping_ratio,eps_naive_eq10,eps_improved_corrected,eps_eq12_as_printed,\
         omega0_tc_improved",
    ),
    (
        "kinetic-haff",
        "t_over_t0,time,temperature_emd,temperature_emd_error,temperature_dsmc,haff,\
         haff_maxwellian",
    ),
    (
        "kinetic-a2",
        "eps,a2_dsmc,a2_dsmc_error,a2_van_noije_ernst,a2_second_sonine,a3_second_sonine",
    ),
    (
        "kinetic-viscoelastic",
        "time,temperature_emd,temperature_dsmc",
    ),
    ("kinetic-viscoelastic-exponent", "time,local_exponent"),
    (
        "kinetic-shear",
        "dimension,packing_fraction,restitution,dsmc,particles,box_over_lc,seeds,\
         fit_end_collisions,k_over_kc,growth_per_collision,growth_error,growth_theory",
    ),
    (
        "kinetic-shear-haff",
        "collisions_above,t_over_haff_above,error_above,collisions_below,t_over_haff_below,\
         error_below",
    ),
    (
        "kinetic-soft-sphere",
        "packing_fraction,time,temperature_soft_sphere,temperature_emd_exact,\
         temperature_emd_fast,temperature_dsmc,soft_over_emd,soft_over_emd_error,\
         contact_time_fraction,delay_model",
    ),
    (
        "kinetic-shear-modes",
        "case,k_over_kc,collisions_per_particle,transverse_energy,transverse_energy_error",
    ),
    (
        "kinetic-usf",
        "alpha,dsmc,a_star,a_star_error,pxx,pxx_error,pyy,pyy_error,pzz,pzz_error,pxy,\
         pxy_error,grad_a_star,grad_pxx,grad_pyy,grad_pxy,bgk_a_star",
    ),
    (
        "kinetic-viscosity",
        "alpha,eta,eta_error,grad,chapman_enskog",
    ),
    ("kinetic-green-kubo", "phi,dsmc,eta,eta_error,theory"),
    (
        "kinetic-diffusion",
        "dsmc,refine,phi,alpha,ratio,ratio_error,theory,box_over_critical",
    ),
    (
        "kinetic-conductivity",
        "dsmc,z,temperature,kappa,kappa_error,theory",
    ),
    (
        "rough-hcs",
        "dsmc,alpha,beta,ratio,ratio_error,theory_ratio,cooling,cooling_error,theory_cooling,\
         sonine_ratio,sonine_cooling,a2,a2_error,sonine_a20,sonine_largest_cumulant",
    ),
    (
        "giese-fig1",
        "collision,e_tr,eps,eta,e_tr_running_mean,equipartition_per_collision",
    ),
    ("giese-fig1-spectrum", "rod,mode,w,equipartition"),
    ("giese-fig2", "modes,collision,eta,eta_equilibrium"),
    (
        "giese-fig3",
        "eps2,density_a,cdf_a,density_b,cdf_b,density_c,cdf_c",
    ),
    (
        "giese-deterministic",
        "gamma,kappa,closed_form,closed_form_general,eps",
    ),
    ("giese-ed-mc", "time,chain_md,ed_mc_glauber,ed_mc_tabulated"),
];

/// The IDs (every CSV stem that is not an extra `ID-name.csv`).
fn ids() -> Vec<&'static str> {
    CSVS.iter()
        .map(|c| c.0)
        .filter(|id| {
            ![
                "mp2011-table1-errors",
                "kinetic-viscoelastic-exponent",
                "kinetic-shear-haff",
                "kinetic-shear-modes",
                "giese-fig1-spectrum",
            ]
            .contains(id)
        })
        .collect()
}

#[test]
fn all_quick_writes_every_file() {
    let dir = std::env::temp_dir().join(format!("haff-reproduce-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = dir.to_str().expect("UTF-8 path");
    let gallery = dir.join("gallery.md");
    let page = gallery.to_str().expect("UTF-8 path");
    let stdout = stdout_of(&[
        "reproduce",
        "all",
        "--quick",
        "--out",
        out,
        "--gallery",
        page,
    ]);
    // The gallery shows every item's figure, links relative to the page.
    let shown = std::fs::read_to_string(&gallery).expect("gallery");
    for id in ids() {
        assert!(
            shown.contains(&format!("## {id}: ")),
            "{id} not in the gallery"
        );
        assert!(
            shown.contains(&format!("]({id}.png)")),
            "{id}.png not shown"
        );
    }
    // One summary line per ID.
    for id in ids() {
        assert_eq!(
            stdout.lines().filter(|l| l.starts_with(id)).count(),
            1,
            "{id} in {stdout}"
        );
        for ext in ["png", "svg", "md"] {
            let path = dir.join(format!("{id}.{ext}"));
            let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
            assert!(size > 100, "{} missing or empty", path.display());
        }
        let md = std::fs::read_to_string(dir.join(format!("{id}.md"))).unwrap();
        assert!(md.starts_with(&format!("# {id}")), "{md}");
        assert!(md.contains("**Paper.**") && md.contains("**Difference.**"));
    }
    for (stem, header) in CSVS {
        let text = std::fs::read_to_string(dir.join(format!("{stem}.csv")))
            .unwrap_or_else(|_| panic!("{stem}.csv"));
        let mut lines = text.lines();
        let got: String = lines.next().unwrap().split_whitespace().collect();
        let want: String = header.split_whitespace().collect();
        assert_eq!(got, want, "{stem}.csv");
        let columns = want.split(',').count();
        let rows: Vec<&str> = lines.collect();
        assert!(rows.len() >= 10, "{stem}.csv has {} rows", rows.len());
        assert!(
            rows.iter().all(|r| r.split(',').count() == columns),
            "{stem}"
        );
    }
    // Numbers of the notes that the library tests pin: the asymptote prefactor (3/2)^(2/3)
    // (laws::asymptotic_power_laws) and the misprinted h_2 (docs/errata.md).
    let fig2 = std::fs::read_to_string(dir.join("mp2011-fig2.md")).unwrap();
    assert!(fig2.contains("(3/2)^(2/3) = 1.31037"), "{fig2}");
    let table5 = std::fs::read_to_string(dir.join("sp2008-table5.md")).unwrap();
    assert!(
        table5.contains("computed -1.1534488580952887991"),
        "{table5}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn list_names_every_id() {
    let list = stdout_of(&["reproduce", "--list"]);
    assert_eq!(list.lines().count(), ids().len(), "{list}");
    for id in ids() {
        assert!(
            list.lines()
                .any(|l| l.split_whitespace().next() == Some(id)),
            "{id} not listed: {list}"
        );
    }
}

#[test]
fn unknown_id_is_rejected() {
    assert_rejected(&["reproduce", "mp2011-fig9"], "ID");
    let stderr = String::from_utf8_lossy(&haff(&["reproduce", "mp2011-fig9"]).stderr).to_string();
    assert!(stderr.contains("mp2011-fig9"), "{stderr}");
    for id in ids() {
        assert!(
            stderr.contains(id),
            "{id} not among the valid IDs: {stderr}"
        );
    }
}
