//! The docs cannot drift (issue 39): every TOML and shell block of README.md and
//! docs/guide/*.md is extracted and checked against the `haff` binary, and every relative
//! link of those pages resolves. The oracle is the binary itself: a run file shown in the
//! docs must validate (`haff run --check`) and, when small, run; a command shown must run
//! or, when marked `no_run`, at least name a subcommand and flags that exist.
//!
//! The info string of a fenced block says how it is checked:
//! - `toml`: a complete run file, validated and run (`haff run FILE`); keep it to a second.
//! - `toml,no_run`: a complete run file, validated only (`haff run --check FILE`).
//! - `toml,fragment`: part of a run file, merged key by key over [`BASE`] and validated
//!   (a fragment that gives `collision.law` replaces the base's `[collision]`).
//! - `toml,file`: another TOML file (a study file): written for the page's commands only.
//! - A TOML block whose first line is `# file: NAME` is written to NAME in the page's
//!   scratch directory (which holds a link `docs` to the repository's docs/), in page order,
//!   for the page's later commands.
//! - `sh`: commands run in order in the scratch directory with `haff` on PATH (a `\` at
//!   the end of a line continues it; `cargo run --release --` means `haff`); each must
//!   exit 0.
//! - `sh,no_run`: commands not run; each `haff SUB ...` in them is run with `--help`
//!   appended, which exits 0 only if the subcommand and its flags exist.
//! - `python` (run by python/tests/test_docs.py), `text`, `json`, `csv`: not checked here.
//!   Any other language is refused, so that no example escapes the checks.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The run file that fragments complete.
const BASE: &str = "[system]\ndimension = 3\nparticles = 100\npacking_fraction = 0.1\n\
                    [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
                    [run]\ncollisions_per_particle = 2\nsamples = 3\n";

/// Languages shown but checked elsewhere or not at all.
const UNCHECKED: [&str; 4] = ["python", "text", "json", "csv"];

struct Block {
    line: usize,
    language: String,
    attributes: Vec<String>,
    text: String,
}

fn repository() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// README.md and the guide's pages, in a fixed order.
fn pages() -> Vec<PathBuf> {
    let root = repository();
    let mut guide: Vec<PathBuf> = std::fs::read_dir(root.join("docs/guide"))
        .expect("docs/guide")
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    guide.sort();
    std::iter::once(root.join("README.md"))
        .chain(guide)
        .collect()
}

/// The fenced code blocks of a Markdown text (fences of backticks, possibly indented).
fn blocks(text: &str) -> Vec<Block> {
    let mut found = Vec::new();
    let mut open: Option<(usize, String, Vec<String>, String, String)> = None;
    for (index, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        match open.take() {
            None => {
                if let Some(info) = trimmed.strip_prefix("```") {
                    let indent = line[..line.len() - trimmed.len()].to_string();
                    let mut words = info.trim().split(',').map(|w| w.trim().to_string());
                    let language = words.next().unwrap_or_default();
                    open = Some((index + 1, language, words.collect(), indent, String::new()));
                }
            }
            Some((start, language, attributes, indent, body)) => {
                if trimmed.starts_with("```") {
                    found.push(Block {
                        line: start,
                        language,
                        attributes,
                        text: body,
                    });
                } else {
                    let body = body + line.strip_prefix(indent.as_str()).unwrap_or(line) + "\n";
                    open = Some((start, language, attributes, indent, body));
                }
            }
        }
    }
    found
}

/// A scratch directory per page, with `docs` linking to the repository's docs/ and `haff`
/// in its `bin/`.
fn scratch(page: &Path) -> PathBuf {
    let stem = page.file_stem().unwrap().to_string_lossy().to_string();
    let dir = std::env::temp_dir().join(format!("haff-docs-{}-{stem}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("bin")).unwrap();
    std::os::unix::fs::symlink(
        repository().join("docs").canonicalize().unwrap(),
        dir.join("docs"),
    )
    .unwrap();
    std::os::unix::fs::symlink(env!("CARGO_BIN_EXE_haff"), dir.join("bin/haff")).unwrap();
    dir
}

/// Runs `command` by `sh -c` in `dir` with its `bin/` first on PATH: None or the failure.
fn shell(dir: &Path, command: &str) -> Option<String> {
    let path = format!(
        "{}:{}",
        dir.join("bin").display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let out = Command::new("sh")
        .arg("-c")
        .arg(command)
        .current_dir(dir)
        .env("PATH", path)
        .output()
        .expect("sh runs");
    (!out.status.success()).then(|| {
        format!(
            "`{command}` exited with {}: {}{}",
            out.status,
            String::from_utf8_lossy(&out.stderr).trim(),
            String::from_utf8_lossy(&out.stdout)
                .lines()
                .take(3)
                .collect::<Vec<_>>()
                .join(" / ")
        )
    })
}

/// The commands of a shell block: continued lines joined, comments and blank lines dropped,
/// `cargo run --release --` read as `haff`.
fn commands(text: &str) -> Vec<String> {
    let joined = text.replace("\\\n", " ");
    joined
        .lines()
        .map(|l| {
            strip_comment(l)
                .trim()
                .replace("cargo run --release --", "haff")
        })
        .filter(|l| !l.is_empty())
        .collect()
}

/// A line without its shell comment (a `#` at the start or after a space, outside quotes).
fn strip_comment(line: &str) -> &str {
    let (mut single, mut double) = (false, false);
    let mut previous = ' ';
    for (i, c) in line.char_indices() {
        match c {
            '\'' if !double => single = !single,
            '"' if !single => double = !double,
            '#' if !single && !double && previous.is_whitespace() => return &line[..i],
            _ => {}
        }
        previous = c;
    }
    line
}

/// `haff SUB ...` of a command not run, up to the first pipe, redirection or list, with
/// `--help` appended; None if the command does not call haff.
fn help_of(command: &str) -> Option<String> {
    let start = command.find("haff ")?;
    let rest = &command[start..];
    let end = rest.find(['|', '>', '<', ';', '&']).unwrap_or(rest.len());
    Some(format!("{} --help", rest[..end].trim()))
}

/// `text` merged key by key over `base` (tables recursively; other values replaced).
fn merge(base: &mut toml::Table, text: &toml::Table) {
    for (key, value) in text {
        match (base.get_mut(key), value) {
            (Some(toml::Value::Table(b)), toml::Value::Table(v)) => merge(b, v),
            _ => {
                base.insert(key.clone(), value.clone());
            }
        }
    }
}

/// The name a TOML block asks to be written under (`# file: NAME` on its first line).
fn file_name(text: &str) -> Option<String> {
    let first = text.lines().next()?.trim();
    let name = first
        .strip_prefix('#')?
        .trim()
        .strip_prefix("file:")?
        .trim();
    Some(name.to_string())
}

/// Checks one block of `page`; the failures.
fn check(dir: &Path, block: &Block) -> Vec<String> {
    let fail = |m: String| vec![format!("line {} ({}): {m}", block.line, block.language)];
    let attributes: Vec<&str> = block.attributes.iter().map(String::as_str).collect();
    match block.language.as_str() {
        "toml" => {
            let name = file_name(&block.text).unwrap_or(format!("example-{}.toml", block.line));
            let path = dir.join(&name);
            if let Some(parent) = path.parent() {
                std::fs::create_dir_all(parent).unwrap();
            }
            match attributes.as_slice() {
                [] | ["no_run"] => {
                    std::fs::write(&path, &block.text).unwrap();
                    let checked = shell(dir, &format!("haff run --check '{name}' > /dev/null"));
                    if let Some(failure) = checked {
                        return fail(failure);
                    }
                    if attributes.is_empty() {
                        let out = format!("out-{}", block.line);
                        if let Some(failure) = shell(dir, &format!("haff run '{name}' --out {out}"))
                        {
                            return fail(failure);
                        }
                    }
                    vec![]
                }
                ["fragment"] => {
                    let fragment: toml::Table = match block.text.parse() {
                        Ok(t) => t,
                        Err(e) => return fail(format!("not TOML: {e}")),
                    };
                    let mut whole: toml::Table = BASE.parse().unwrap();
                    // A fragment giving another law brings that law's keys: the base's
                    // [collision] (restitution) would be refused beside them.
                    let law = fragment.get("collision").and_then(|c| c.get("law"));
                    if law.is_some() {
                        whole.remove("collision");
                    }
                    merge(&mut whole, &fragment);
                    std::fs::write(&path, toml::to_string(&whole).unwrap()).unwrap();
                    shell(dir, &format!("haff run --check '{name}' > /dev/null"))
                        .map_or(vec![], fail)
                }
                ["file"] => {
                    std::fs::write(&path, &block.text).unwrap();
                    vec![]
                }
                other => fail(format!("unknown attributes {other:?}")),
            }
        }
        "sh" => match attributes.as_slice() {
            [] => commands(&block.text)
                .iter()
                .find_map(|c| shell(dir, c))
                .map_or(vec![], fail),
            ["no_run"] => commands(&block.text)
                .iter()
                .filter_map(|c| help_of(c))
                .filter_map(|c| shell(dir, &format!("{c} > /dev/null")))
                .flat_map(fail)
                .collect(),
            other => fail(format!("unknown attributes {other:?}")),
        },
        language if UNCHECKED.contains(&language) => vec![],
        other => fail(format!(
            "a block in `{other}`: use toml, sh, python, text, json or csv (see tests/docs.rs)"
        )),
    }
}

#[test]
fn every_example_of_the_readme_and_the_guide_runs() {
    let mut failures = Vec::new();
    let mut checked = 0;
    for page in pages() {
        let text = std::fs::read_to_string(&page).unwrap();
        let dir = scratch(&page);
        for block in blocks(&text) {
            checked += 1;
            for failure in check(&dir, &block) {
                failures.push(format!("{}: {failure}", page.display()));
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
    assert!(checked > 0, "no code blocks found");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Relative links `](target)` of a Markdown text, with their line numbers.
fn links(text: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    let mut fenced = false;
    for (index, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        }
        if fenced {
            continue;
        }
        for (start, _) in line.match_indices("](") {
            let rest = &line[start + 2..];
            if let Some(end) = rest.find(')') {
                let target = rest[..end].split('#').next().unwrap_or("").trim();
                if !target.is_empty() && !target.contains("://") && !target.starts_with("mailto:") {
                    found.push((index + 1, target.to_string()));
                }
            }
        }
    }
    found
}

#[test]
fn every_link_of_the_readme_and_the_guide_resolves() {
    let mut failures = Vec::new();
    for page in pages() {
        let text = std::fs::read_to_string(&page).unwrap();
        for (line, target) in links(&text) {
            if !page.parent().unwrap().join(&target).exists() {
                failures.push(format!("{}:{line}: {target}", page.display()));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "broken links:\n{}",
        failures.join("\n")
    );
}

/// The book's table of contents lists every page of the guide, and only pages that exist
/// (mdBook would create the missing ones empty).
#[test]
fn the_summary_lists_every_page() {
    let guide = repository().join("docs/guide");
    let summary = std::fs::read_to_string(guide.join("SUMMARY.md")).expect("SUMMARY.md");
    let listed: Vec<String> = links(&summary).into_iter().map(|(_, t)| t).collect();
    for page in pages().iter().skip(1) {
        let name = page.file_name().unwrap().to_string_lossy().to_string();
        if name != "SUMMARY.md" {
            assert!(listed.contains(&name), "{name} is not in SUMMARY.md");
        }
    }
    assert!(guide.join("book.toml").exists(), "book.toml");
}

#[test]
fn the_extraction_reads_what_the_conventions_say() {
    let text = "a\n```toml,no_run\n# file: a.toml\n[system]\n```\n  ```sh\n  haff run a.toml \\\n    --out x  # a comment\n  ```\n";
    let found = blocks(text);
    assert_eq!(found.len(), 2);
    assert_eq!((found[0].line, found[0].language.as_str()), (2, "toml"));
    assert_eq!(found[0].attributes, ["no_run"]);
    assert_eq!(file_name(&found[0].text).as_deref(), Some("a.toml"));
    assert_eq!(commands(&found[1].text), ["haff run a.toml    --out x"]);
    assert_eq!(
        help_of("mpirun -n 4 haff run x.toml > log").as_deref(),
        Some("haff run x.toml --help")
    );
    assert_eq!(
        strip_comment("haff cor eps --law 'a#b' # c"),
        "haff cor eps --law 'a#b' "
    );
}
