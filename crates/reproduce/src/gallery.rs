//! The gallery of `haff reproduce`: one Markdown page that shows every item's figures with
//! its one-line result and the "Difference" paragraph of its `ID.md` (what agrees with the
//! paper, what does not, and why), linking to the data and the note.

use super::{Entry, Outcome};
use sim::error::{Error, Result};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// `path` relative to the directory `base` if it lies inside it (Markdown links), else as
/// given.
fn relative(path: &Path, base: &Path) -> String {
    let shown: PathBuf = path
        .strip_prefix(base)
        .map_or(path.to_path_buf(), Path::to_path_buf);
    shown.to_string_lossy().replace('\\', "/")
}

/// The paragraph of a note that starts with `**Difference.**` (up to the next blank line).
fn difference(note: &str) -> Option<String> {
    let start = note.find("**Difference.**")?;
    let paragraph = note[start..].split("\n\n").next()?;
    Some(paragraph.split_whitespace().collect::<Vec<_>>().join(" "))
}

/// Writes the gallery of `results` (items run into `out`) to `page`, its links relative to
/// the page's directory.
pub fn write(page: &Path, out: &Path, results: &[(Entry, Outcome)], command: &str) -> Result<()> {
    let base = page.parent().unwrap_or(Path::new(""));
    let mut text = String::new();
    let _ = writeln!(
        text,
        "# The papers, reproduced\n\nEvery figure and table of the three papers and the \
         kinetic theory haff is checked against, recomputed by `{command}` (this page \
         and the files it shows are its output). Each item links its data (CSV) and its note \
         (what the paper shows, what we get, where and why they differ, with numbers).\n"
    );
    for (entry, outcome) in results {
        let _ = writeln!(text, "## {}: {}, {}\n", entry.id, entry.paper, entry.item);
        let _ = writeln!(text, "{}.\n", entry.shows);
        for file in outcome
            .files
            .iter()
            .filter(|f| f.extension().is_some_and(|e| e == "png"))
        {
            let _ = writeln!(text, "![{}]({})\n", entry.id, relative(file, base));
        }
        let _ = writeln!(text, "**Result.** {}\n", outcome.summary);
        let note_path = out.join(format!("{}.md", entry.id));
        let note = std::fs::read_to_string(&note_path).map_err(|e| Error::write(&note_path, e))?;
        if let Some(paragraph) = difference(&note) {
            let _ = writeln!(text, "{paragraph}\n");
        }
        let csvs: Vec<String> = outcome
            .files
            .iter()
            .filter(|f| f.extension().is_some_and(|e| e == "csv"))
            .map(|f| format!("[{}]({})", relative(f, out), relative(f, base)))
            .collect();
        let _ = writeln!(
            text,
            "Data: {}; note: [{}.md]({}).\n",
            csvs.join(", "),
            entry.id,
            relative(&note_path, base)
        );
    }
    sim::output::write_file(page, |w| w.write_all(text.as_bytes()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn difference_paragraph_is_joined_to_one_line() {
        let note = "# x\n\n**Paper.** a\n\n**Difference.** one\ntwo\n\nmore";
        assert_eq!(difference(note).unwrap(), "**Difference.** one two");
        assert_eq!(
            relative(Path::new("docs/r/a.png"), Path::new("docs")),
            "r/a.png"
        );
    }
}
