//! `haff schema`: the JSON Schema of the run file, or the Markdown reference of its keys,
//! both made by `sim::schema` (docs/run-file.schema.json and docs/guide/reference.md are
//! their committed output). No physics.

use crate::error::CliResult;
use crate::output::stdout;
use crate::SchemaArgs;
use std::io::Write;

/// `haff schema [--reference]`.
pub fn schema(args: &SchemaArgs) -> CliResult {
    let text = if args.reference {
        sim::schema::reference_markdown()
    } else {
        sim::schema::run_file_schema_text()
    };
    let mut out = stdout();
    out.write_all(text.as_bytes())?;
    out.flush()?;
    Ok(())
}
