//! Giese, the deterministic limit of Eq. (3) (cold bath) against the paper's closed form
//! and the generalized one.

use super::*;

/// The (gamma, kappa) of docs/giese.md's table whose differences the note prints, with the
/// names of (eps - general form, eps - paper's form).
const PINNED: [(f64, f64, &str, &str); 8] = [
    (0.1, 30.0, "general_g0_1_k30", "paper_g0_1_k30"),
    (0.1, 100.0, "general_g0_1_k100", "paper_g0_1_k100"),
    (0.3, 100.0, "general_g0_3_k100", "paper_g0_3_k100"),
    (0.45, 100.0, "general_g0_45_k100", "paper_g0_45_k100"),
    (0.1, 300.0, "general_g0_1_k300", "paper_g0_1_k300"),
    (0.3, 300.0, "general_g0_3_k300", "paper_g0_3_k300"),
    (0.6173, 100.0, "general_g0_6173_k100", "paper_g0_6173_k100"),
    (0.99, 100.0, "general_g0_99_k100", "paper_g0_99_k100"),
];
const KAPPAS: [f64; 3] = [30.0, 100.0, 300.0];

pub(super) fn deterministic(ctx: &Context) -> Result<Outcome> {
    let id = "giese-deterministic";
    // h kappa: the default of `haff rods deterministic` (0.02), 0.1 in quick mode (the
    // tests of crates/rods/tests/stochastic.rs use 0.1 too).
    let step = if ctx.quick { 0.1 } else { 0.02 };
    let mut gammas = logspace(0.1, 10.0, if ctx.quick { 21 } else { 61 });
    for g in [0.3, 0.45, 0.5, 0.6173, 0.8, 0.9, 0.95, 0.99, 1.0] {
        gammas.extend([g, 1.0 / g]);
    }
    gammas.sort_by(f64::total_cmp);
    gammas.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let cell = |x: f64| {
        if x.is_finite() {
            number(x)
        } else {
            String::new()
        }
    };
    let mut rows = Vec::new();
    let mut by_kappa: Vec<Vec<(f64, f64, f64, f64)>> = Vec::new();
    for &kappa in &KAPPAS {
        let mut curve = Vec::new();
        for &gamma in &gammas {
            let eps = eps_numeric(gamma, kappa, step / kappa);
            let (paper, general) = (
                eps_closed_form(gamma, kappa),
                eps_closed_form_general(gamma, kappa),
            );
            rows.push(vec![
                number(gamma),
                number(kappa),
                cell(paper),
                cell(general),
                number(eps),
            ]);
            curve.push((gamma, eps, paper, general));
        }
        by_kappa.push(curve);
    }
    let mut files = vec![ctx.csv_cells(
        id,
        &[
            "gamma",
            "kappa",
            "closed_form",
            "closed_form_general",
            "eps",
        ],
        rows,
    )?];
    let mut fig = Figure::new(
        "Giese Eq. (3), cold bath: eps(gamma) vs the closed forms",
        "length ratio gamma = l1 / l2",
        "eps",
    )
    .log(true, false);
    for (kappa, curve) in KAPPAS.iter().zip(&by_kappa) {
        fig = fig.line(
            format!("Eq. (3) solved, kappa = {kappa}"),
            curve.iter().map(|c| (c.0, c.1)).collect(),
        );
    }
    // The closed forms at the smallest kappa, where they differ most (clipped at eps = 0.05:
    // both tend to -inf at gamma = 1).
    let k30 = &by_kappa[0];
    let clip = |v: f64| if v > 0.05 { v } else { f64::NAN };
    fig = fig
        .theory(
            "paper: min(gamma, 1/gamma) + ln(kappa |Gamma2 - Gamma1|)/kappa, kappa = 30",
            k30.iter().map(|c| (c.0, clip(c.2))).collect(),
        )
        .theory(
            "generalized: ln(kappa min(Gamma_s, |Gamma2 - Gamma1|))/kappa, kappa = 30",
            k30.iter().map(|c| (c.0, clip(c.3))).collect(),
        );
    files.push(ctx.figure(id, &fig)?);
    let mut err = Figure::new(
        "Giese Eq. (3), cold bath: |eps - closed form|",
        "length ratio gamma = l1 / l2",
        "|eps(Eq. 3) - closed form|",
    )
    .log(true, true);
    let positive = |v: f64| if v > 0.0 { v } else { f64::NAN };
    for (kappa, curve) in KAPPAS.iter().zip(&by_kappa) {
        err = err.line(
            format!("generalized form, kappa = {kappa}"),
            curve
                .iter()
                .map(|c| (c.0, positive((c.1 - c.3).abs())))
                .collect(),
        );
    }
    for (kappa, curve) in KAPPAS.iter().zip(&by_kappa) {
        err = err.theory(
            format!("paper's form, kappa = {kappa}"),
            curve
                .iter()
                .map(|c| (c.0, positive((c.1 - c.2).abs())))
                .collect(),
        );
    }
    files.push(ctx.figure(&format!("{id}-error"), &err)?);

    let mut values = Vec::new();
    let mut table = String::new();
    for (gamma, kappa, general_name, paper_name) in PINNED {
        let eps = eps_numeric(gamma, kappa, step / kappa);
        let dg = eps - eps_closed_form_general(gamma, kappa);
        let dp = eps - eps_closed_form(gamma, kappa);
        let _ = writeln!(
            table,
            "| {gamma} | {kappa} | {} | {} | {} |",
            sig(eps),
            sig(dp),
            sig(dg)
        );
        values.extend([(general_name, dg), (paper_name, dp)]);
    }
    let symmetric =
        (eps_numeric(0.3, 100.0, step / 100.0) - eps_numeric(1.0 / 0.3, 100.0, step / 100.0)).abs();
    let equal = eps_numeric(1.0, 100.0, step / 100.0);
    let at_giese = eps_numeric(GAMMA, 100.0, step / 100.0);
    values.extend([
        ("eps_g0_6173_k100", at_giese),
        ("eps_equal_rods_k100", equal),
        ("symmetry_g0_3_k100", symmetric),
    ]);
    let md = format!(
        "# {id}: the deterministic limit of Eq. (3) against both closed forms\n\n\
         **Paper.** At T_bath = 0 Eq. (3) gives eps = min(gamma, 1/gamma) + \
         ln(kappa |Gamma2 - Gamma1|)/kappa for large kappa (Gamma1 = 1 + gamma, Gamma2 = \
         1 + 1/gamma).\n\n\
         **We get.** `rods::deterministic::eps_numeric` with h kappa = {step} for kappa = 30, \
         100, 300 and {} values of gamma in [0.1, 10], against the paper's form and the \
         generalized one, min(gamma, 1/gamma) + ln(kappa min(Gamma_s, |Gamma2 - \
         Gamma1|))/kappa (docs/giese.md). eps(gamma = 0.6173, kappa = 100) = {}; equal rods: \
         eps = {} (the closed forms are -inf there); |eps(0.3) - eps(1/0.3)| = {}.\n\n\
         | gamma | kappa | eps | eps - paper's form | eps - generalized form |\n\
         |---|---|---|---|---|\n{table}\n\
         **Difference.** The paper's form assumes that the longer rod's first reflection \
         arrives before the shorter rod's second one, i.e. 1/2 < gamma < 2. There it holds \
         once kappa |Gamma2 - Gamma1| >~ 10 (error exponentially small); below gamma = 1/2 \
         (above 2) it is wrong at order ln(...)/kappa (e.g. {} at gamma = 0.1, kappa = 100) \
         while the generalized form leaves an O(kappa^-1.8) remainder ({}); near gamma = 1 \
         both fail (equal rods collide elastically). eps(gamma) = eps(1/gamma).\n",
        gammas.len(),
        sig(at_giese),
        sig(equal),
        sig(symmetric),
        sig(values[3].1),
        sig(values[2].1),
    );
    files.push(ctx.markdown(id, &md)?);
    Ok(Outcome {
        summary: format!(
            "eps - paper's form at gamma = 0.1, kappa = 100: {}; generalized: {}; eps(0.6173, 100) = {}",
            sig(values[3].1),
            sig(values[2].1),
            sig(at_giese)
        ),
        values,
        files,
    })
}
