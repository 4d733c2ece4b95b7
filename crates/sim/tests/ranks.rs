//! A spatial DSMC run of the driver spread over ranks (threads of this process standing for
//! MPI ranks, `sim::parallel::InProcess`) gives the single process's records bit for bit:
//! time series, velocity histograms, modes and S(k), summary; its check-point continues on
//! another number of ranks; rough particles too. So does a homogeneous DSMC run of the
//! block scheme. Runs that cannot spread are refused naming the key. (The MPI
//! build is checked through mpirun in crates/cli/tests/mpi.rs.)

use sim::parallel::{Communicator, InProcess, Local};
use sim::{RunDescription, Simulation};
use std::path::Path;
use std::sync::Arc;

fn description(extra: &str) -> RunDescription {
    let text = format!(
        "[system]\ndimension = 3\nparticles = 3000\npacking_fraction = 0.1\nseed = 9\n\
         [collision]\nlaw = \"viscoelastic\"\nbeta = 0.2\n\
         [run]\nengine = \"dsmc\"\ndsmc_scheme = \"spatial\"\ncollisions_per_particle = 40\n\
         samples = 8\nhistogram_at = [0.0, 20.0]\n{extra}\
         [output]\nmodes = true\nstructure = true\n"
    );
    RunDescription::from_toml(&text, Path::new("ranks.toml")).unwrap()
}

/// Everything a run records, as text (bit-exact: floats in their shortest round-trip form).
fn records(simulation: &Simulation) -> String {
    format!(
        "{:?}\n{:?}\n{:?}\n{:?}\n{:?}\n{:?}",
        simulation.samples(),
        simulation.histograms(),
        simulation.space_records(),
        simulation.counters(),
        simulation.species_samples(),
        simulation.report().section("rotation"),
    )
}

fn comm(c: InProcess) -> Arc<dyn Communicator> {
    Arc::new(c)
}

/// The homogeneous engine's block scheme (blocks of 150 in a mixture of 3000 particles: 20
/// blocks), with velocity histograms.
fn blocks(extra: &str) -> RunDescription {
    homogeneous(&format!(
        "dsmc_scheme = \"blocks\"\nblock_size = 150\n{extra}"
    ))
}

/// The mixture of [`blocks`] in the homogeneous engine, its scheme from `scheme`.
fn homogeneous(scheme: &str) -> RunDescription {
    let text = format!(
        "[system]\ndimension = 3\npacking_fraction = 0.1\nseed = 9\n\
         particles = 3000\nspecies = [{{ diameter = 1.0, mass = 1.0, fraction = 0.6 }}, \
         {{ diameter = 1.6, mass = 3.0, fraction = 0.4 }}]\n\
         [collision]\nlaw = \"viscoelastic\"\nbeta = 0.2\n\
         [run]\nengine = \"dsmc\"\n{scheme}\
         collisions_per_particle = 40\nsamples = 8\nhistogram_at = [0.0, 20.0]\n"
    );
    RunDescription::from_toml(&text, Path::new("blocks.toml")).unwrap()
}

#[test]
fn a_run_on_1_2_4_ranks_records_the_same() {
    assert_same_on_ranks(&description(""));
}

#[test]
fn a_blocks_run_on_1_2_4_ranks_records_the_same() {
    assert_same_on_ranks(&blocks(""));
}

/// Rough particles of the block scheme (Walton's friction: the sliding contacts are
/// summed over the ranks), on 1, 2 and 4 ranks and resumed on 3 and 1.
#[test]
fn a_rough_blocks_run_spreads_and_resumes() {
    let mut d = blocks("");
    d.collision.tangential_restitution = Some(sim::description::RestitutionValue::One(0.4));
    d.collision.friction = Some(0.3);
    d.system.species.as_mut().unwrap()[1].inertia = Some(0.25);
    assert_same_on_ranks(&d);
    assert_resumes(&d, "rough");
}

/// Rough particles of the spatial scheme (Walton's friction; a mixture whose second
/// species has an inertia of its own): the records cross the slabs with their spins, the
/// sliding contacts are summed over the ranks; on 1, 2 and 4 ranks and resumed on 3 and
/// 1, the records (rotational temperatures per species, the `rotation` section) are the
/// single process's bit for bit.
#[test]
fn a_rough_spatial_run_spreads_and_resumes() {
    let text = "[system]\ndimension = 3\nparticles = 3000\npacking_fraction = 0.1\nseed = 9\n\
                species = [{ diameter = 1.0, mass = 1.0, fraction = 0.6 }, \
                { diameter = 1.6, mass = 3.0, fraction = 0.4, inertia = 0.25 }]\n\
                [collision]\nlaw = \"viscoelastic\"\nbeta = 0.2\n\
                tangential_restitution = 0.4\nfriction = 0.3\n\
                [run]\nengine = \"dsmc\"\ndsmc_scheme = \"spatial\"\ncollisions_per_particle = 40\n\
                samples = 8\nhistogram_at = [0.0, 20.0]\n";
    let d = RunDescription::from_toml(text, Path::new("rough.toml")).unwrap();
    assert_same_on_ranks(&d);
    assert_resumes(&d, "rough-spatial");
}

fn assert_same_on_ranks(d: &RunDescription) {
    let mut single = Simulation::new_on(d, Arc::new(Local)).unwrap();
    single.run(&mut (), None).unwrap();
    let want = records(&single);
    assert!(single.rank_reports().is_none());
    for ranks in [1, 2, 4] {
        let got = InProcess::run(ranks, |c| {
            let mut s = Simulation::new_on(d, comm(c)).unwrap();
            s.run(&mut (), None).unwrap();
            (records(&s), s.rank_reports())
        });
        for (rank, (text, reports)) in got.iter().enumerate() {
            if *text != want {
                let (a, b): (Vec<&str>, Vec<&str>) =
                    (text.split(", ").collect(), want.split(", ").collect());
                let i = a.iter().zip(&b).position(|(x, y)| x != y).unwrap_or(0);
                panic!(
                    "{ranks} ranks, rank {rank}: records differ at item {i}: {:?} vs {:?}",
                    &a[i.saturating_sub(3)..i + 2],
                    &b[i.saturating_sub(3)..i + 2]
                );
            }
            assert_eq!(reports.is_some(), ranks > 1);
        }
    }
}

/// A check-point written on 2 ranks (by rank 0: the whole gas) resumes on 3 ranks and on
/// one, and ends as the uninterrupted run.
#[test]
fn a_checkpoint_from_2_ranks_resumes_on_3_and_on_1() {
    assert_resumes(&description(""), "spatial");
    assert_resumes(&blocks(""), "blocks");
}

fn assert_resumes(d: &RunDescription, name: &str) {
    let mut single = Simulation::new_on(d, Arc::new(Local)).unwrap();
    single.run(&mut (), None).unwrap();
    let want = records(&single);
    let dir = std::env::temp_dir().join(format!("haff-ranks-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    InProcess::run(2, |c| {
        let mut s = Simulation::new_on(d, comm(c)).unwrap();
        s.set_checkpoints(&dir, Some(3));
        s.run(&mut (), Some(4)).unwrap();
    });
    let resumed = InProcess::run(3, |c| {
        let mut s = Simulation::resume_on(&dir, comm(c)).unwrap();
        s.run(&mut (), None).unwrap();
        records(&s)
    });
    assert!(resumed.iter().all(|r| *r == want), "resumed on 3 ranks");
    let mut one = Simulation::resume_on(&dir, Arc::new(Local)).unwrap();
    one.run(&mut (), None).unwrap();
    let got = records(&one);
    if got != want {
        let (a, b): (Vec<&str>, Vec<&str>) =
            (got.split(", ").collect(), want.split(", ").collect());
        let i = a.iter().zip(&b).position(|(x, y)| x != y).unwrap_or(0);
        panic!(
            "resumed on 1 rank: differ at item {i}: {:?} vs {:?}",
            &a[i.saturating_sub(3)..i + 2],
            &b[i.saturating_sub(3)..i + 2]
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `run.ranks` must match the launch; only spatial DSMC and the block scheme spread; no
/// more ranks than planes of cells or blocks.
#[test]
fn runs_that_cannot_spread_are_refused() {
    let message = |e: sim::Error| {
        assert!(e.is_input(), "{e}");
        e.to_string()
    };
    let e = message(
        Simulation::new_on(&description("ranks = 2\n"), Arc::new(Local))
            .err()
            .unwrap(),
    );
    assert!(
        e.contains("run.ranks") && e.contains("2 ranks and runs on 1"),
        "{e}"
    );
    let event_driven = RunDescription::from_toml(
        "[system]\nparticles = 100\npacking_fraction = 0.1\n[collision]\nlaw = \"constant\"\n\
         restitution = 0.9\n[run]\ncollisions_per_particle = 1\nsamples = 2\n",
        Path::new("e.toml"),
    )
    .unwrap();
    let errors = InProcess::run(2, |c| {
        message(Simulation::new_on(&event_driven, comm(c)).err().unwrap())
    });
    assert!(
        errors[0].contains("run.engine") && errors[0].contains("2 ranks"),
        "{}",
        errors[0]
    );
    let wide = description("collision_cell_width = 5.0\n");
    let errors = InProcess::run(8, |c| {
        message(Simulation::new_on(&wide, comm(c)).err().unwrap())
    });
    assert!(
        errors[0].contains("run.ranks") && errors[0].contains("at most"),
        "{}",
        errors[0]
    );
    let few_blocks = homogeneous("dsmc_scheme = \"blocks\"\nblock_size = 1500\n");
    let errors = InProcess::run(3, |c| {
        message(Simulation::new_on(&few_blocks, comm(c)).err().unwrap())
    });
    assert!(
        errors[0].contains("run.ranks") && errors[0].contains("at most the 2 blocks"),
        "{}",
        errors[0]
    );
    let exact = homogeneous("dsmc_scheme = \"exact\"\n");
    let errors = InProcess::run(2, |c| {
        message(Simulation::new_on(&exact, comm(c)).err().unwrap())
    });
    assert!(
        errors[0].contains("run.engine") && errors[0].contains("\"blocks\""),
        "{}",
        errors[0]
    );
    let bad = RunDescription::from_toml(
        "[system]\nparticles = 100\npacking_fraction = 0.1\n[collision]\nlaw = \"constant\"\n\
         restitution = 0.9\n[run]\ncollisions_per_particle = 1\nsamples = 2\nranks = 3\n",
        Path::new("e.toml"),
    )
    .unwrap();
    let e = message(Simulation::new_on(&bad, Arc::new(Local)).err().unwrap());
    assert!(e.contains("run.ranks") && e.contains("spatial"), "{e}");
}

/// A mixture's check-point at any sample resumes with each species' collisions: the
/// records are permuted every step, so the saved system may start with any species, and
/// a restored engine orders its species by first appearance (a state once wrote the
/// collisions in the saving engine's order: one species' were taken for another's,
/// found when the rough gas's check-point at its sixth sample resumed with other
/// collision frequencies per species).
#[test]
fn a_mixture_resumes_its_species_collisions_from_any_sample() {
    let mut rough = blocks("");
    rough.collision.tangential_restitution = Some(sim::description::RestitutionValue::One(0.4));
    rough.system.species.as_mut().unwrap()[1].inertia = Some(0.25);
    for d in [blocks(""), rough] {
        let rows = |s: &Simulation| format!("{:?}", s.species_samples());
        let mut single = Simulation::new_on(&d, Arc::new(Local)).unwrap();
        single.run(&mut (), None).unwrap();
        for every in 1..=7 {
            let dir = std::env::temp_dir()
                .join(format!("haff-ranks-species-{every}-{}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            let mut s = Simulation::new_on(&d, Arc::new(Local)).unwrap();
            s.set_checkpoints(&dir, Some(every));
            s.run(&mut (), Some(7)).unwrap();
            let mut resumed = Simulation::resume_on(&dir, Arc::new(Local)).unwrap();
            resumed.run(&mut (), None).unwrap();
            assert_eq!(
                rows(&resumed),
                rows(&single),
                "check-point every {every} samples"
            );
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }
}
