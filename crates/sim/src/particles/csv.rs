//! `csv`: a first line `# box = Lx Ly Lz` (one side per dimension), a header line naming
//! the columns, one line per particle. Columns: `x,y,z` (as many as dimensions, required),
//! `vx,vy,vz` (all or none), and optional `diameter`, `mass`, `species` (an index from 0),
//! `wx,wy,wz` (spins; disks: `wz` alone). Unknown columns are refused, naming them.

use super::{number, Configuration, Fault, Vec3};
use crate::output;
use std::io::{self, Write};

const AXES: [&str; 3] = ["x", "y", "z"];

/// The columns of a file in `dimension` dimensions, in the order haff writes them.
fn known(dimension: usize) -> Vec<String> {
    let mut names: Vec<String> = AXES[..dimension].iter().map(|a| a.to_string()).collect();
    names.extend(AXES[..dimension].iter().map(|a| format!("v{a}")));
    names.extend(["diameter", "mass", "species"].map(String::from));
    names.extend(spin_columns(dimension));
    names
}

fn spin_columns(dimension: usize) -> Vec<String> {
    match dimension {
        2 => vec!["wz".into()],
        3 => AXES.iter().map(|a| format!("w{a}")).collect(),
        _ => Vec::new(),
    }
}

pub(super) fn parse(text: &str, dimension: usize) -> Result<Configuration, Fault> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let (_, first) = lines
        .next()
        .ok_or_else(|| ("line 1".to_string(), "the file is empty".to_string()))?;
    let sides = first
        .trim()
        .strip_prefix('#')
        .and_then(|rest| rest.trim().strip_prefix("box"))
        .and_then(|rest| rest.trim().strip_prefix('='))
        .ok_or_else(|| {
            (
                "line 1".to_string(),
                "expected `# box = Lx Ly Lz` (one side per dimension)".to_string(),
            )
        })?
        .split_whitespace()
        .map(|s| number(s, 1, "box"))
        .collect::<Result<Vec<f64>, Fault>>()?;
    if sides.len() != dimension {
        return Err((
            "line 1".into(),
            format!("{} box sides for dimension {dimension}", sides.len()),
        ));
    }
    let (_, header) = lines
        .next()
        .ok_or_else(|| ("line 2".to_string(), "no header line".to_string()))?;
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let allowed = known(dimension);
    if let Some(bad) = names.iter().find(|n| !allowed.iter().any(|a| a == *n)) {
        return Err((
            "line 2".into(),
            format!(
                "column `{bad}` is not one of {} (dimension {dimension})",
                allowed.join(",")
            ),
        ));
    }
    let at = |name: &str| names.iter().position(|n| *n == name);
    let axes: Vec<Option<usize>> = AXES[..dimension].iter().map(|a| at(a)).collect();
    if let Some(k) = axes.iter().position(Option::is_none) {
        return Err((
            "line 2".into(),
            format!("column `{}` is missing (positions are required)", AXES[k]),
        ));
    }
    let velocity: Vec<Option<usize>> = AXES[..dimension]
        .iter()
        .map(|a| at(&format!("v{a}")))
        .collect();
    let spin_names = spin_columns(dimension);
    let spin: Vec<Option<usize>> = spin_names.iter().map(|n| at(n)).collect();
    for (what, columns) in [("velocity", &velocity), ("spin", &spin)] {
        let given = columns.iter().filter(|c| c.is_some()).count();
        if given != 0 && given != columns.len() {
            return Err((
                "line 2".into(),
                format!("some {what} columns are missing: give all of them or none"),
            ));
        }
    }
    let (diameter, mass, species) = (at("diameter"), at("mass"), at("species"));
    let mut c = Configuration {
        dimension,
        sides,
        positions: Vec::new(),
        velocities: velocity[0].map(|_| Vec::new()),
        diameters: diameter.map(|_| Vec::new()),
        masses: mass.map(|_| Vec::new()),
        species: species.map(|_| Vec::new()),
        spins: spin.first().copied().flatten().map(|_| Vec::new()),
        time: None,
    };
    let mut cells: Vec<&str> = Vec::with_capacity(names.len());
    for (line, text) in lines {
        if text.trim().is_empty() {
            continue;
        }
        cells.clear();
        cells.extend(text.split(',').map(str::trim));
        if cells.len() != names.len() {
            return Err((
                format!("line {line}"),
                format!("{} cells for {} columns", cells.len(), names.len()),
            ));
        }
        let get = |k: usize| number(cells[k], line, names[k]);
        let vector = |columns: &[Option<usize>]| -> Result<Vec3, Fault> {
            let mut v = [0.0; 3];
            if dimension == 2 && columns.len() == 1 {
                v[2] = get(columns[0].unwrap_or(0))?;
                return Ok(v);
            }
            for (k, column) in columns.iter().enumerate() {
                v[k] = get(column.unwrap_or(0))?;
            }
            Ok(v)
        };
        c.positions.push(vector(&axes)?);
        if let Some(list) = &mut c.velocities {
            list.push(vector(&velocity)?);
        }
        if let Some(list) = &mut c.spins {
            list.push(vector(&spin)?);
        }
        if let (Some(list), Some(k)) = (&mut c.diameters, diameter) {
            list.push(get(k)?);
        }
        if let (Some(list), Some(k)) = (&mut c.masses, mass) {
            list.push(get(k)?);
        }
        if let (Some(list), Some(k)) = (&mut c.species, species) {
            let s = cells[k];
            list.push(s.parse::<usize>().map_err(|_| {
                (
                    format!("line {line}"),
                    format!("column `species`: `{s}` is not an index from 0"),
                )
            })?);
        }
    }
    Ok(c)
}

pub(super) fn write(out: &mut dyn Write, c: &Configuration) -> io::Result<()> {
    let d = c.dimension;
    let sides: Vec<String> = c.sides.iter().map(|x| output::number(*x)).collect();
    writeln!(out, "# box = {}", sides.join(" "))?;
    let mut header: Vec<String> = AXES[..d].iter().map(|a| a.to_string()).collect();
    if c.velocities.is_some() {
        header.extend(AXES[..d].iter().map(|a| format!("v{a}")));
    }
    for (name, given) in [
        ("diameter", c.diameters.is_some()),
        ("mass", c.masses.is_some()),
        ("species", c.species.is_some()),
    ] {
        if given {
            header.push(name.into());
        }
    }
    if c.spins.is_some() {
        header.extend(spin_columns(d));
    }
    writeln!(out, "{}", header.join(","))?;
    let spin_axes: &[usize] = match d {
        2 => &[2],
        3 => &[0, 1, 2],
        _ => &[],
    };
    let mut row = Vec::with_capacity(header.len());
    for i in 0..c.len() {
        row.clear();
        row.extend(c.positions[i][..d].iter().map(|x| output::number(*x)));
        if let Some(v) = &c.velocities {
            row.extend(v[i][..d].iter().map(|x| output::number(*x)));
        }
        if let Some(list) = &c.diameters {
            row.push(output::number(list[i]));
        }
        if let Some(list) = &c.masses {
            row.push(output::number(list[i]));
        }
        if let Some(list) = &c.species {
            row.push(list[i].to_string());
        }
        if let Some(w) = &c.spins {
            row.extend(spin_axes.iter().map(|&k| output::number(w[i][k])));
        }
        writeln!(out, "{}", row.join(","))?;
    }
    Ok(())
}
