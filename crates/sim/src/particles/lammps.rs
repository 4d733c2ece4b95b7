//! LAMMPS `dump custom` text files (the format of `dump ID group custom N file id type x y
//! z vx vy vz radius ...`, as LAMMPS writes them and OVITO reads them): frames of
//! `ITEM: TIMESTEP`, `ITEM: NUMBER OF ATOMS`, `ITEM: BOX BOUNDS` (three lines `lo hi`, also in
//! 2D) and `ITEM: ATOMS <columns>`. Columns read: `id` (particles are ordered by it),
//! `type` (species = type - 1), `x y z` (or unwrapped `xu yu zu`, or scaled `xs ys zs`),
//! `vx vy vz`, `radius` or `diameter`, `mass`, `omegax omegay omegaz`; others are ignored.
//! Positions are shifted by the box's lower corner and wrapped into it (unwrapped
//! coordinates of a periodic box).

use super::{number, Configuration, Fault, Vec3};
use crate::output;
use std::io::{self, Write};

/// One frame's lines: the line number of its `ITEM: TIMESTEP` and its text lines.
fn frames(text: &str) -> Vec<usize> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| l.trim_start().starts_with("ITEM: TIMESTEP"))
        .map(|(i, _)| i)
        .collect()
}

pub(super) fn parse_dump(text: &str, dimension: usize, frame: i64) -> Result<Configuration, Fault> {
    let starts = frames(text);
    if starts.is_empty() {
        return Err((
            "line 1".into(),
            "no `ITEM: TIMESTEP`: not a LAMMPS dump".into(),
        ));
    }
    let index = super::frame_index(frame, starts.len())?;
    let lines: Vec<&str> = text.lines().collect();
    let mut at = starts[index];
    let line_no = |i: usize| i + 1;
    let expect = |i: usize, item: &str| -> Result<(), Fault> {
        match lines.get(i) {
            Some(l) if l.trim_start().starts_with(item) => Ok(()),
            _ => Err((format!("line {}", line_no(i)), format!("expected `{item}`"))),
        }
    };
    // A timestep counts steps, not time: not kept.
    expect(at, "ITEM: TIMESTEP")?;
    at += 2;
    expect(at, "ITEM: NUMBER OF ATOMS")?;
    let n_text = lines.get(at + 1).map_or("", |l| l.trim());
    let n: usize = n_text.parse().map_err(|_| {
        (
            format!("line {}", line_no(at + 1)),
            format!("NUMBER OF ATOMS: `{n_text}` is not a count"),
        )
    })?;
    at += 2;
    expect(at, "ITEM: BOX BOUNDS")?;
    if lines[at].contains("xy") {
        return Err((
            format!("line {}", line_no(at)),
            "a triclinic box; allowed: an orthogonal one".into(),
        ));
    }
    let mut lows = [0.0; 3];
    let mut sides = Vec::new();
    for (k, low) in lows.iter_mut().enumerate() {
        let i = at + 1 + k;
        let fields: Vec<&str> = lines
            .get(i)
            .map_or(Vec::new(), |l| l.split_whitespace().collect());
        if fields.len() < 2 {
            return Err((format!("line {}", line_no(i)), "expected `lo hi`".into()));
        }
        let lo = number(fields[0], line_no(i), "BOX BOUNDS lo")?;
        let hi = number(fields[1], line_no(i), "BOX BOUNDS hi")?;
        *low = lo;
        if k < dimension {
            sides.push(hi - lo);
        }
    }
    at += 4;
    expect(at, "ITEM: ATOMS")?;
    let names: Vec<&str> = lines[at].split_whitespace().skip(2).collect();
    let column = |name: &str| names.iter().position(|n| *n == name);
    let axes = ["x", "y", "z"];
    let (position, scaled) = {
        let plain: Vec<Option<usize>> = axes.iter().map(|a| column(a)).collect();
        let unwrapped: Vec<Option<usize>> = axes.iter().map(|a| column(&format!("{a}u"))).collect();
        let scaled: Vec<Option<usize>> = axes.iter().map(|a| column(&format!("{a}s"))).collect();
        let complete = |c: &Vec<Option<usize>>| c[..dimension].iter().all(Option::is_some);
        if complete(&plain) {
            (plain, false)
        } else if complete(&unwrapped) {
            (unwrapped, false)
        } else if complete(&scaled) {
            (scaled, true)
        } else {
            return Err((
                format!("line {}", line_no(at)),
                format!(
                    "no position columns (x y{} , xu ..., or xs ...)",
                    if dimension == 3 { " z" } else { "" }
                ),
            ));
        }
    };
    let velocity: Vec<Option<usize>> = ["vx", "vy", "vz"].iter().map(|a| column(a)).collect();
    let has_velocity = velocity[..dimension].iter().all(Option::is_some);
    let spin: Vec<Option<usize>> = ["omegax", "omegay", "omegaz"]
        .iter()
        .map(|a| column(a))
        .collect();
    let has_spin = spin.iter().all(Option::is_some);
    let (radius, diameter) = (column("radius"), column("diameter"));
    let (mass, kind, id) = (column("mass"), column("type"), column("id"));
    // A count beyond the lines there are is refused below, line by line: reserve no more
    // than the file can hold.
    let n_reserved = n.min(lines.len());
    let mut rows: Vec<(u64, usize)> = Vec::with_capacity(n_reserved);
    let mut c = Configuration {
        dimension,
        sides,
        positions: Vec::with_capacity(n_reserved),
        velocities: has_velocity.then(|| Vec::with_capacity(n_reserved)),
        diameters: (radius.is_some() || diameter.is_some()).then(|| Vec::with_capacity(n_reserved)),
        masses: mass.map(|_| Vec::with_capacity(n_reserved)),
        species: kind.map(|_| Vec::with_capacity(n_reserved)),
        spins: has_spin.then(|| Vec::with_capacity(n_reserved)),
        time: None,
    };
    for r in 0..n {
        let i = at + 1 + r;
        let Some(line) = lines.get(i) else {
            return Err((
                format!("line {}", line_no(i)),
                format!("the frame ends after {r} of {n} atoms"),
            ));
        };
        let cells: Vec<&str> = line.split_whitespace().collect();
        if cells.len() < names.len() {
            return Err((
                format!("line {}", line_no(i)),
                format!("{} values for {} columns", cells.len(), names.len()),
            ));
        }
        let get = |k: usize| number(cells[k], line_no(i), names[k]);
        let vector = |columns: &[Option<usize>]| -> Result<Vec3, Fault> {
            let mut v = [0.0; 3];
            for (k, col) in columns.iter().enumerate() {
                if let Some(col) = col {
                    v[k] = get(*col)?;
                }
            }
            Ok(v)
        };
        let mut p = vector(&position[..dimension])?;
        for k in 0..dimension {
            let l = c.sides[k];
            p[k] = if scaled { p[k] * l } else { p[k] - lows[k] };
            // Unwrapped or slightly outside (LAMMPS re-wraps only at reneighboring).
            if p[k].is_finite() && !(0.0..l).contains(&p[k]) {
                p[k] -= l * (p[k] / l).floor();
                if p[k] >= l {
                    p[k] = 0.0;
                }
            }
        }
        c.positions.push(p);
        if let Some(list) = &mut c.velocities {
            list.push(vector(&velocity[..dimension])?);
        }
        if let Some(list) = &mut c.spins {
            list.push(vector(&spin)?);
        }
        if let Some(list) = &mut c.diameters {
            list.push(match (radius, diameter) {
                (Some(k), _) => 2.0 * get(k)?,
                (None, Some(k)) => get(k)?,
                _ => unreachable!("diameters only with a radius or diameter column"),
            });
        }
        if let (Some(list), Some(k)) = (&mut c.masses, mass) {
            list.push(get(k)?);
        }
        if let (Some(list), Some(k)) = (&mut c.species, kind) {
            let t = cells[k];
            let t: usize = t.parse().ok().filter(|t| *t >= 1).ok_or_else(|| {
                (
                    format!("line {}", line_no(i)),
                    format!("column `type`: `{t}` is not a LAMMPS atom type (1, 2, ...)"),
                )
            })?;
            list.push(t - 1);
        }
        let key = match id {
            Some(k) => cells[k].parse::<u64>().map_err(|_| {
                (
                    format!("line {}", line_no(i)),
                    format!("column `id`: `{}` is not an atom id", cells[k]),
                )
            })?,
            None => r as u64,
        };
        rows.push((key, r));
    }
    // Dumps list atoms in any order: by id.
    rows.sort_unstable();
    if let Some(w) = rows.windows(2).find(|w| w[0].0 == w[1].0) {
        return Err((
            format!("line {}", line_no(at + 1 + w[1].1)),
            format!("column `id`: atom id {} appears twice", w[0].0),
        ));
    }
    let order: Vec<usize> = rows.iter().map(|(_, r)| *r).collect();
    Ok(permuted(c, &order))
}

/// The configuration with its particles in `order`.
pub(super) fn permuted(c: Configuration, order: &[usize]) -> Configuration {
    fn pick<T: Copy>(list: Option<Vec<T>>, order: &[usize]) -> Option<Vec<T>> {
        list.map(|l| order.iter().map(|&i| l[i]).collect())
    }
    Configuration {
        positions: order.iter().map(|&i| c.positions[i]).collect(),
        velocities: pick(c.velocities, order),
        diameters: pick(c.diameters, order),
        masses: pick(c.masses, order),
        species: pick(c.species, order),
        spins: pick(c.spins, order),
        ..c
    }
}

/// One `dump custom` frame at `timestep`: `id type x y z [vx vy vz] radius [mass]
/// [omegax omegay omegaz]` (2D: z = 0 in a box of z bounds -0.5 0.5, as LAMMPS'
/// `dimension 2`).
pub(super) fn write_dump(out: &mut dyn Write, c: &Configuration, timestep: u64) -> io::Result<()> {
    let d = c.dimension;
    writeln!(out, "ITEM: TIMESTEP\n{timestep}")?;
    writeln!(out, "ITEM: NUMBER OF ATOMS\n{}", c.len())?;
    writeln!(out, "ITEM: BOX BOUNDS pp pp pp")?;
    for k in 0..3 {
        if k < d {
            writeln!(out, "0 {}", output::number(c.sides[k]))?;
        } else {
            writeln!(out, "-0.5 0.5")?;
        }
    }
    let names = [
        "x y z",
        "vx vy vz",
        "radius",
        "mass",
        "omegax omegay omegaz",
    ];
    let columns = super::column_names(c, names, " ");
    writeln!(out, "ITEM: ATOMS id type {columns}")?;
    let mut row = String::new();
    for i in 0..c.len() {
        row.clear();
        let kind = c.species.as_ref().map_or(1, |s| s[i] + 1);
        row += &format!("{} {kind}", i + 1);
        super::push_columns(&mut row, c, i);
        writeln!(out, "{row}")?;
    }
    Ok(())
}
