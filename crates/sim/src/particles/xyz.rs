//! Extended XYZ (the libAtoms/ASE/OVITO convention): per frame a line with the count, a
//! comment line of `key=value` pairs — `Lattice="ax ay az bx by bz cx cy cz"` (here an
//! orthogonal box: b and c along y and z), `Properties=name:type:columns:...` (types S, R,
//! I, L), optionally `Time=` — then one line per particle. Properties read: `type` (an
//! integer from 1, species + 1, as OVITO and LAMMPS number types; what haff writes, and
//! what ASE reads as an array beside its element symbols) or `species` (names: integers
//! are the species index, other names, such as ASE's element symbols, are numbered in the
//! order they first appear), `pos`, `velo` (or `vel`, `velocities`), `radius` or
//! `diameter`, `mass`, `omega` (or `angular_velocity`); others are skipped. 2D files hold
//! z = 0 in a cell of height 1 with `pbc="T T F"`.

use super::{number, Configuration, Fault, Vec3};
use crate::output;
use std::io::{self, Write};

/// The `key=value` pairs of a comment line (values in double quotes may hold spaces).
fn pairs(line: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut chars = line.chars().peekable();
    loop {
        while chars.peek().is_some_and(|c| c.is_whitespace()) {
            chars.next();
        }
        let mut key = String::new();
        while let Some(&c) = chars.peek() {
            if c == '=' || c.is_whitespace() {
                break;
            }
            key.push(c);
            chars.next();
        }
        if key.is_empty() {
            return out;
        }
        let mut value = String::new();
        if chars.peek() == Some(&'=') {
            chars.next();
            if chars.peek() == Some(&'"') {
                chars.next();
                for c in chars.by_ref() {
                    if c == '"' {
                        break;
                    }
                    value.push(c);
                }
            } else {
                while let Some(&c) = chars.peek() {
                    if c.is_whitespace() {
                        break;
                    }
                    value.push(c);
                    chars.next();
                }
            }
        }
        out.push((key, value));
    }
}

/// What a property column holds.
#[derive(Clone, Copy, PartialEq)]
enum Role {
    Species,
    Type,
    Position,
    Velocity,
    Radius,
    Diameter,
    Mass,
    Spin,
    Skip,
}

pub(super) fn parse(text: &str, dimension: usize, frame: i64) -> Result<Configuration, Fault> {
    let lines: Vec<&str> = text.lines().collect();
    // The frames' first lines.
    let mut starts = Vec::new();
    let mut at = 0;
    while at < lines.len() {
        if lines[at].trim().is_empty() {
            at += 1;
            continue;
        }
        let n: usize = lines[at].trim().parse().map_err(|_| {
            (
                format!("line {}", at + 1),
                format!(
                    "`{}` is not a particle count (a frame's first line)",
                    lines[at].trim()
                ),
            )
        })?;
        starts.push((at, n));
        at = at.saturating_add(n).saturating_add(2);
    }
    if starts.is_empty() {
        return Err(("line 1".into(), "the file is empty".into()));
    }
    let index = super::frame_index(frame, starts.len())?;
    let (first, n) = starts[index];
    let comment_line = first + 2;
    let comment = lines.get(first + 1).copied().unwrap_or("");
    let info = pairs(comment);
    let get = |key: &str| {
        info.iter()
            .find(|(k, _)| k.eq_ignore_ascii_case(key))
            .map(|(_, v)| v.as_str())
    };
    let lattice = get("Lattice").ok_or_else(|| {
        (
            format!("line {comment_line}"),
            "no `Lattice=\"...\"`: the box is required".to_string(),
        )
    })?;
    let cell = lattice
        .split_whitespace()
        .map(|x| number(x, comment_line, "Lattice"))
        .collect::<Result<Vec<f64>, Fault>>()?;
    if cell.len() != 9 {
        return Err((
            format!("line {comment_line}"),
            format!("Lattice has {} numbers; allowed: 9", cell.len()),
        ));
    }
    let off_diagonal = [1, 2, 3, 5, 6, 7];
    if off_diagonal.iter().any(|&k| cell[k] != 0.0) {
        return Err((
            format!("line {comment_line}"),
            "Lattice is not orthogonal along x, y, z; allowed: an orthogonal box".into(),
        ));
    }
    let sides: Vec<f64> = [cell[0], cell[4], cell[8]][..dimension].to_vec();
    let properties = get("Properties").unwrap_or("species:S:1:pos:R:3");
    let fields: Vec<&str> = properties.split(':').collect();
    if !fields.len().is_multiple_of(3) {
        return Err((
            format!("line {comment_line}"),
            format!("Properties `{properties}` is not name:type:columns triples"),
        ));
    }
    let mut roles: Vec<(Role, usize)> = Vec::new();
    for triple in fields.chunks(3) {
        let width: usize = triple[2].parse().map_err(|_| {
            (
                format!("line {comment_line}"),
                format!("Properties: `{}` is not a column count", triple[2]),
            )
        })?;
        let role = match triple[0].to_ascii_lowercase().as_str() {
            "species" => Role::Species,
            "type" => Role::Type,
            "pos" | "position" | "positions" => Role::Position,
            "velo" | "vel" | "velocities" | "velocity" => Role::Velocity,
            "radius" | "radii" => Role::Radius,
            "diameter" => Role::Diameter,
            "mass" | "masses" => Role::Mass,
            "omega" | "angular_velocity" | "angular_velocities" => Role::Spin,
            _ => Role::Skip,
        };
        let vector = matches!(role, Role::Position | Role::Velocity | Role::Spin);
        if role != Role::Skip && width != if vector { 3 } else { 1 } {
            return Err((
                format!("line {comment_line}"),
                format!("Properties: `{}` has {width} columns", triple[0]),
            ));
        }
        roles.push((role, width));
    }
    let has = |r: Role| roles.iter().any(|(role, _)| *role == r);
    if !has(Role::Position) {
        return Err((
            format!("line {comment_line}"),
            "Properties has no `pos`".into(),
        ));
    }
    // A count beyond the lines there are is refused below: reserve no more than that.
    let n_reserved = n.min(lines.len());
    let mut c = Configuration {
        dimension,
        sides,
        positions: Vec::with_capacity(n_reserved),
        velocities: has(Role::Velocity).then(|| Vec::with_capacity(n_reserved)),
        diameters: (has(Role::Radius) || has(Role::Diameter))
            .then(|| Vec::with_capacity(n_reserved)),
        masses: has(Role::Mass).then(|| Vec::with_capacity(n_reserved)),
        species: (has(Role::Species) || has(Role::Type)).then(|| Vec::with_capacity(n_reserved)),
        spins: has(Role::Spin).then(|| Vec::with_capacity(n_reserved)),
        time: get("Time")
            .map(|t| number(t, comment_line, "Time"))
            .transpose()?,
    };
    let mut names: Vec<String> = Vec::new();
    for r in 0..n {
        let line_no = first + 3 + r;
        let Some(line) = lines.get(line_no - 1) else {
            return Err((
                format!("line {line_no}"),
                format!("the frame ends after {r} of {n} particles"),
            ));
        };
        let mut cells = line.split_whitespace();
        for (role, width) in &roles {
            let mut take = |what: &str| -> Result<&str, Fault> {
                cells.next().ok_or_else(|| {
                    (
                        format!("line {line_no}"),
                        format!("the line ends before `{what}`"),
                    )
                })
            };
            let mut vector = |what: &str| -> Result<Vec3, Fault> {
                let mut v = [0.0; 3];
                for x in v.iter_mut() {
                    *x = number(take(what)?, line_no, what)?;
                }
                Ok(v)
            };
            match role {
                Role::Position => {
                    let mut p = vector("pos")?;
                    p[dimension..].fill(0.0);
                    c.positions.push(p);
                }
                Role::Velocity => {
                    let mut v = vector("velo")?;
                    v[dimension..].fill(0.0);
                    if let Some(list) = &mut c.velocities {
                        list.push(v);
                    }
                }
                Role::Spin => {
                    let w = vector("omega")?;
                    if let Some(list) = &mut c.spins {
                        list.push(w);
                    }
                }
                Role::Radius | Role::Diameter | Role::Mass => {
                    let x = number(take("a number")?, line_no, "radius, diameter or mass")?;
                    match role {
                        Role::Radius => c.diameters.as_mut().map(|l| l.push(2.0 * x)),
                        Role::Diameter => c.diameters.as_mut().map(|l| l.push(x)),
                        _ => c.masses.as_mut().map(|l| l.push(x)),
                    };
                }
                Role::Species => {
                    let name = take("species")?;
                    let index = match name.parse::<usize>() {
                        Ok(i) => i,
                        Err(_) => match names.iter().position(|s| s == name) {
                            Some(i) => i,
                            None => {
                                names.push(name.to_string());
                                names.len() - 1
                            }
                        },
                    };
                    if let Some(list) = &mut c.species {
                        list.push(index);
                    }
                }
                Role::Type => {
                    let t = take("type")?;
                    let index = t.parse::<usize>().ok().filter(|t| *t >= 1).ok_or_else(|| {
                        (
                            format!("line {line_no}"),
                            format!("column `type`: `{t}` is not a type (1, 2, ...)"),
                        )
                    })?;
                    if let Some(list) = &mut c.species {
                        list.push(index - 1);
                    }
                }
                Role::Skip => {
                    for _ in 0..*width {
                        take("a skipped column")?;
                    }
                }
            }
        }
    }
    Ok(c)
}

/// One frame: `type:I:1:pos:R:3[:velo:R:3]:radius:R:1[:mass:R:1][:omega:R:3]`, the type
/// species + 1.
pub(super) fn write(out: &mut dyn Write, c: &Configuration) -> io::Result<()> {
    let d = c.dimension;
    let side = |k: usize| {
        if k < d {
            output::number(c.sides[k])
        } else {
            "1".into()
        }
    };
    let names = ["pos:R:3", "velo:R:3", "radius:R:1", "mass:R:1", "omega:R:3"];
    let properties = format!("type:I:1:{}", super::column_names(c, names, ":"));
    let pbc = ["T T T", "T F F", "T T F", "T T T"][d.min(3)];
    writeln!(out, "{}", c.len())?;
    let time = c
        .time
        .map_or(String::new(), |t| format!(" Time={}", output::number(t)));
    writeln!(
        out,
        "Lattice=\"{} 0 0 0 {} 0 0 0 {}\" Properties={properties} pbc=\"{pbc}\"{time}",
        side(0),
        side(1),
        side(2)
    )?;
    let mut row = String::new();
    for i in 0..c.len() {
        row.clear();
        row += &(c.species.as_ref().map_or(0, |s| s[i]) + 1).to_string();
        super::push_columns(&mut row, c, i);
        writeln!(out, "{row}")?;
    }
    Ok(())
}
