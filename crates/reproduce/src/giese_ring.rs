//! Giese's event-driven + Monte Carlo method (ED + MC: hard rods with a stochastic
//! coefficient of restitution and per-rod bath temperatures) against the rod-chain MD it
//! replaces, on the ring of `docs/data/giese-ring.toml` (the run of `haff rods chain`).

use super::{sig, Context, Entry, Outcome};
use sim::error::Result;
use sim::rod_ring::{RingDescription, RingRun};

/// The ring of docs/giese.md, and the p(eps^2) table its tabulated law reads.
const RING: &str = include_str!("../data/giese-ring.toml");
const TABLE: &str = include_str!("../data/giese-table-gamma0.6173.json");

pub fn entries() -> Vec<Entry> {
    vec![Entry {
        id: "giese-ed-mc",
        paper: "Giese",
        item: "ED + MC vs rod chain",
        shows: "E_tr(t) of a ring of rods: chain MD vs ED + MC (Glauber and tabulated laws)",
        typical_seconds: 55.0,
        run: ed_mc,
    }]
}

fn ed_mc(ctx: &Context) -> Result<Outcome> {
    let id = "giese-ed-mc";
    let table = ctx.out.join(format!("{id}-table.json"));
    std::fs::create_dir_all(&ctx.out).map_err(|e| sim::error::Error::write(&ctx.out, e))?;
    sim::output::write_file(&table, |w| w.write_all(TABLE.as_bytes()))?;
    let mut description: RingDescription =
        toml::from_str(RING).map_err(|e| super::numerical("docs/data/giese-ring.toml", e))?;
    description.run.table = Some(table.clone());
    if ctx.quick {
        description.chain.rods = 20;
        description.run.samples = 21;
        description.run.repeats = 1;
    }
    let mut run = RingRun::new(&description)?;
    run.run(&mut (), None)?;
    let share = run.equipartition_share();
    let curves = run.curves();
    // E_tr over its equipartition value at each sample, per curve (sums over repeats
    // cancel in the ratio).
    let ratio = |rows: &[sim::rod_ring::EnergyRow]| -> Vec<(f64, f64)> {
        rows.iter()
            .map(|r| (r.time, r.translational_energy / (share * r.total_energy)))
            .collect()
    };
    let series: Vec<(String, Vec<(f64, f64)>)> = curves
        .iter()
        .map(|(name, rows)| (name.clone(), ratio(rows)))
        .collect();
    let times: Vec<f64> = series[0].1.iter().map(|p| p.0).collect();
    let rows: Vec<Vec<f64>> = times
        .iter()
        .enumerate()
        .map(|(k, &t)| {
            std::iter::once(t)
                .chain(series.iter().map(|(_, s)| s[k].1))
                .collect()
        })
        .collect();
    let mut files = vec![ctx.csv(
        id,
        &["time", "chain_md", "ed_mc_glauber", "ed_mc_tabulated"],
        &rows,
    )?];
    files.push(table);
    let late = |s: &[(f64, f64)]| {
        let tail = &s[s.len() / 2..];
        tail.iter().map(|p| p.1).sum::<f64>() / tail.len() as f64
    };
    let (chain_late, glauber_late, tabulated_late) =
        (late(&series[0].1), late(&series[1].1), late(&series[2].1));
    let early = |s: &[(f64, f64)]| s[1].1;
    let (glauber_early, tabulated_early) = (
        early(&series[1].1) / early(&series[0].1),
        early(&series[2].1) / early(&series[0].1),
    );
    let mut fig = sim::plot::Figure::new(
        format!(
            "Giese: ring of {} rods, E_tr / equipartition (chain MD vs ED + MC)",
            description.chain.rods
        ),
        "time t",
        "E_tr / E_tr(equipartition)",
    )
    .log(false, true);
    for (name, points) in &series {
        fig = fig.line(name.as_str(), points.clone());
    }
    fig = fig.theory(
        "equipartition with the modes",
        vec![(times[0], 1.0), (times[times.len() - 1], 1.0)],
    );
    files.push(ctx.figure(id, &fig)?);
    let md = format!(
        "# {id}: Giese's ED + MC against the rod chain\n\n\
         **Paper.** Event-driven MD of rigid rods whose collisions draw eps from the \
         stochastic law of Eq. (3), the modes of each rod kept as a bath temperature \
         (Monte Carlo), replaces the MD of the vibrating rods and relaxes to the same \
         equipartition.\n\n\
         **We get** ({} rods, {} modes, {} repeat(s), to t = {}): late-time E_tr over \
         equipartition {} (chain MD), {} (ED + MC, Glauber law), {} (ED + MC, tabulated \
         p(eps^2)); early (second sample) E_tr relative to the chain: Glauber {}, tabulated \
         {}.\n\n\
         **Difference.** All three relax to equipartition with the modes; the way there \
         differs: the Glauber law (Giese's analytic approximation) cools the rods faster \
         than the chain early on, the tabulated law of Eq. (3) follows the chain more \
         closely (docs/giese.md).\n",
        description.chain.rods,
        description.chain.modes,
        description.run.repeats,
        sig(description.run.end_time),
        sig(chain_late),
        sig(glauber_late),
        sig(tabulated_late),
        sig(glauber_early),
        sig(tabulated_early),
    );
    files.push(ctx.markdown(id, &md)?);
    Ok(Outcome {
        summary: format!(
            "late E_tr / equipartition: chain {}, Glauber {}, tabulated {}",
            sig(chain_late),
            sig(glauber_late),
            sig(tabulated_late)
        ),
        values: vec![
            ("chain_late", chain_late),
            ("glauber_late", glauber_late),
            ("tabulated_late", tabulated_late),
        ],
        files,
    })
}
