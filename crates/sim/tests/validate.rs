//! Bad run descriptions are refused before anything runs, with an input error naming the
//! key (what the CLI prints with exit code 2, and Python will raise).

use sim::{Error, Simulation};

const GOOD: &str = "[system]\nparticles = 300\npacking_fraction = 0.05\n\
                    [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
                    [run]\ncollisions_per_particle = 10\nsamples = 4\n";

/// The key of the input error of `toml`.
fn refused_key(toml: &str) -> String {
    match Simulation::from_toml(toml, "bad.toml".as_ref()) {
        Err(Error::Input { key, .. }) => key,
        Err(other) => panic!("{toml}: not an input error: {other}"),
        Ok(_) => panic!("{toml}: accepted"),
    }
}

#[test]
fn errors_name_the_key() {
    for (from, to, key) in [
        (
            "restitution = 0.9",
            "restitution = 1.5",
            "collision.restitution",
        ),
        ("law = \"constant\"", "law = \"plastic\"", "collision.law"),
        ("particles = 300", "particles = 1", "system.particles"),
        (
            "packing_fraction = 0.05",
            "packing_fraction = 0.65",
            "system.packing_fraction",
        ),
        (
            "samples = 4",
            "samples = 4\nspacing = \"cubic\"",
            "run.spacing",
        ),
        ("samples = 4", "samples = 4\nengine = \"md\"", "run.engine"),
        (
            "samples = 4",
            "samples = 4\nblock_size = 64",
            "run.block_size",
        ),
        (
            "samples = 4",
            "samples = 4\nend_time = 3.0",
            "run.collisions_per_particle",
        ),
        (
            "samples = 4",
            "samples = 4\nhistogram_at = [11.0]",
            "run.histogram_at",
        ),
        (
            "restitution = 0.9",
            "restitution = 0.9\nmodes = 3",
            "collision.modes",
        ),
        (
            "particles = 300",
            "particles = \"many\"",
            "system.particles",
        ),
    ] {
        let toml = GOOD.replace(from, to);
        assert_eq!(refused_key(&toml), key, "{toml}");
    }
}

#[test]
fn text_that_is_not_toml_names_the_file() {
    match Simulation::from_toml("[system\n", "bad.toml".as_ref()) {
        Err(error @ Error::RunFile { .. }) => {
            assert!(error.is_input() && error.to_string().starts_with("bad.toml: "))
        }
        other => panic!("{:?}", other.err()),
    }
}

/// An unknown key or value is answered with the closest allowed name when one is close
/// (issue 39: "unknown key `restituton` in [collision]; did you mean `restitution`?"), and
/// with the allowed names always; a name far from all gets the list alone.
#[test]
fn unknown_names_suggest_the_closest() {
    let file = |collision: &str| {
        format!(
            "[system]\nparticles = 10\npacking_fraction = 0.1\n[collision]\n{collision}\n\
             [run]\ncollisions_per_particle = 1\n"
        )
    };
    let refusal = |text: &str| {
        sim::RunDescription::from_toml(text, "t.toml".as_ref())
            .unwrap_err()
            .to_string()
    };
    let e = refusal(&file("law = \"constant\"\nrestituton = 0.9"));
    assert!(
        e.starts_with(
            "collision.restituton: unknown key `restituton` in [collision]; did you mean \
             `restitution`? (allowed: `law`, `restitution`,"
        ),
        "{e}"
    );
    let e = refusal(&file("law = \"constnt\"\nrestitution = 0.9"));
    assert!(
        e.starts_with(
            "collision.law: unknown value `constnt`; did you mean `constant`? (allowed: \
             `constant`, `dashpot`, `viscoelastic`, `stochastic`)"
        ),
        "{e}"
    );
    let e = refusal(&file("law = \"constant\"\nrestitution = 0.9\nwobble = 1"));
    assert!(
        e.starts_with("collision.wobble: unknown key `wobble` in [collision]; allowed: `law`"),
        "{e}"
    );
    assert!(!e.contains("did you mean"), "{e}");
}
