//! `haff schema`: the committed docs/run-file.schema.json and docs/guide/reference.md are
//! what the command prints now (the oracle: the files a user and an editor read must be
//! the ones the description types make; that the schema itself is right is the business of
//! crates/sim/tests/schema.rs).

mod common;

use common::stdout_of;
use std::path::Path;

/// Compares `file` (relative to the repository) with what `haff ARGS` prints.
fn assert_current(file: &str, args: &[&str]) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(file);
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    let printed = stdout_of(args);
    if committed != printed {
        let line = committed
            .lines()
            .zip(printed.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| committed.lines().count().min(printed.lines().count()));
        panic!(
            "{file} is not what `haff {}` prints (first difference at line {}): regenerate it \
             from the repository's root with\n    cargo run --release -- {} > {file}",
            args.join(" "),
            line + 1,
            args.join(" ")
        );
    }
}

#[test]
fn the_committed_schema_is_current() {
    assert_current("docs/run-file.schema.json", &["schema"]);
}

#[test]
fn the_committed_reference_is_current() {
    assert_current("docs/guide/reference.md", &["schema", "--reference"]);
}

#[test]
fn the_schema_is_json_with_its_title() {
    let schema: serde_json::Value = serde_json::from_str(&stdout_of(&["schema"])).unwrap();
    assert_eq!(schema["title"], "haff run file");
    assert_eq!(
        schema["$schema"],
        "https://json-schema.org/draft/2020-12/schema"
    );
    assert_eq!(schema["additionalProperties"], false);
}
