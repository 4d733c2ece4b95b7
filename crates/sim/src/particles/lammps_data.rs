//! LAMMPS data files of `atom_style sphere` (the format of `read_data` and `write_data`,
//! docs.lammps.org/read_data.html): a title line, a header (`N atoms`, `N atom types`,
//! `xlo xhi`, `ylo yhi`, `zlo zhi`, optionally `xy xz yz`), then sections. `Atoms # sphere`
//! lines are `atom-ID atom-type diameter density x y z [ix iy iz]`; `Velocities` lines are
//! `atom-ID vx vy vz omegax omegay omegaz`; other sections (`Pair Coeffs`, ...) are
//! skipped. `#` starts a comment. Atoms are ordered by id (LAMMPS writes them in any
//! order), species = type - 1, positions shifted by the box's lower corner and wrapped into
//! it (as `read_data` remaps atoms into a periodic box; image flags are checked, not kept).
//!
//! Mass: LAMMPS turns the density into the mass as `rmass *= 4.0*MY_PI/3.0 * r*r*r` for r
//! = diameter / 2 > 0, else mass = density (`AtomVecSphere::data_atom_post`,
//! src/atom_vec_sphere.cpp) — the volume of a sphere also in 2D: LAMMPS "29 Sep 2021 -
//! Update 2" (Debian 12) reads and writes 2D files so (crates/sim/tests/lammps_data.rs
//! compares with its dumped masses bit for bit). The writer picks the density whose
//! product is the mass when one exists (for ~9 in 10 masses), else the nearest: masses
//! come back within one ulp.

use super::{number, Configuration, Fault, Vec3};
use crate::output;
use std::io::{self, Write};

/// LAMMPS' `4.0*MY_PI/3.0` of `AtomVecSphere::data_atom_post` in "29 Sep 2021" (the
/// double 0x1.0c152382d7365p+2; later versions write `MY_4PI3`, the literal, one ulp more:
/// their masses may differ from these by an ulp or two).
const FOUR_PI_3: f64 = 4.0 * std::f64::consts::PI / 3.0;

/// The mass LAMMPS gives an atom of `diameter` and `density`, in its order of operations.
pub(crate) fn mass(diameter: f64, density: f64) -> f64 {
    let r = 0.5 * diameter;
    if r > 0.0 {
        density * (FOUR_PI_3 * r * r * r)
    } else {
        density
    }
}

/// The density that LAMMPS turns into `mass` (see [`mass`]): the exact one among the
/// floats next to mass / volume, else the nearest.
pub(crate) fn density(diameter: f64, mass_wanted: f64) -> f64 {
    let guess = mass_wanted / mass(diameter, 1.0);
    let mut best = guess;
    let (mut below, mut above) = (guess, guess);
    for _ in 0..4 {
        below = below.next_down();
        above = above.next_up();
        for candidate in [below, above] {
            let error = |d: f64| (mass(diameter, d) - mass_wanted).abs();
            if error(candidate) < error(best) {
                best = candidate;
            }
        }
    }
    best
}

/// A line without its comment, trimmed.
fn content(line: &str) -> &str {
    line.split('#').next().unwrap_or("").trim()
}

/// A section's first line starts with a letter (data lines with a number).
fn is_section(line: &str) -> bool {
    content(line)
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic())
}

/// What the header says.
#[derive(Default)]
struct Header {
    atoms: Option<usize>,
    types: Option<usize>,
    bounds: [Option<(f64, f64)>; 3],
}

/// The header lines up to the first section (index `lines.len()` if none).
fn header(lines: &[&str]) -> Result<(Header, usize), Fault> {
    let mut h = Header::default();
    for (i, line) in lines.iter().enumerate().skip(1) {
        let at = || format!("line {}", i + 1);
        if is_section(line) {
            return Ok((h, i));
        }
        let words: Vec<&str> = content(line).split_whitespace().collect();
        if words.is_empty() {
            continue;
        }
        let values = words
            .iter()
            .take_while(|w| w.parse::<f64>().is_ok())
            .count();
        let keyword = words[values..].join(" ");
        let count = |name: &str| -> Result<usize, Fault> {
            if values != 1 {
                return Err((at(), format!("`{name}` takes one count")));
            }
            words[0]
                .parse::<usize>()
                .map_err(|_| (at(), format!("`{}` is not a count of {name}", words[0])))
        };
        let floats = |k: usize| -> Result<Vec<f64>, Fault> {
            if values != k {
                return Err((at(), format!("`{keyword}` takes {k} numbers")));
            }
            words[..k]
                .iter()
                .map(|w| number(w, i + 1, &keyword))
                .collect()
        };
        match keyword.as_str() {
            "atoms" => h.atoms = Some(count("atoms")?),
            "atom types" => h.types = Some(count("atom types")?),
            "xlo xhi" | "ylo yhi" | "zlo zhi" => {
                let k = ["xlo xhi", "ylo yhi", "zlo zhi"]
                    .iter()
                    .position(|n| *n == keyword)
                    .unwrap_or(0);
                let b = floats(2)?;
                h.bounds[k] = Some((b[0], b[1]));
            }
            "xy xz yz" => {
                let t = floats(3)?;
                if t.iter().any(|x| *x != 0.0) {
                    return Err((
                        at(),
                        format!(
                            "a tilted (triclinic) box, xy xz yz = {} {} {}; allowed: an \
                             orthogonal box (tilts 0)",
                            t[0], t[1], t[2]
                        ),
                    ));
                }
            }
            // Other counts (bonds, ellipsoids, ...) belong to other atom styles' sections,
            // which are skipped.
            _ if values > 0 => {}
            _ => {
                return Err((
                    at(),
                    format!(
                        "`{}` is not a header line of a LAMMPS data file",
                        line.trim()
                    ),
                ))
            }
        }
    }
    Ok((h, lines.len()))
}

/// A section's data lines: (line index, words).
type Rows<'a> = Vec<(usize, Vec<&'a str>)>;

/// The data lines of the section starting at line index `start` (its keyword line): the
/// next `n` lines with content, each as (line index, words), or a fault if the section
/// ends first.
fn rows<'a>(
    lines: &[&'a str],
    start: usize,
    n: usize,
    name: &str,
) -> Result<(Rows<'a>, usize), Fault> {
    let mut out = Vec::with_capacity(n.min(lines.len()));
    let mut i = start + 1;
    while out.len() < n {
        match lines.get(i) {
            Some(line) if !is_section(line) => {
                let words: Vec<&str> = content(line).split_whitespace().collect();
                if !words.is_empty() {
                    out.push((i, words));
                }
            }
            _ => {
                return Err((
                    format!("line {}", i + 1),
                    format!("the {name} section ends after {} of {n} atoms", out.len()),
                ))
            }
        }
        i += 1;
    }
    Ok((out, i))
}

pub(super) fn parse_data(text: &str, dimension: usize, frame: i64) -> Result<Configuration, Fault> {
    super::frame_index(frame, 1)?;
    let lines: Vec<&str> = text.lines().collect();
    if lines.is_empty() {
        return Err(("line 1".into(), "the file is empty".into()));
    }
    let (h, mut i) = header(&lines)?;
    let n = h
        .atoms
        .ok_or_else(|| ("header".to_string(), "no `N atoms` line".to_string()))?;
    let types = h.types.unwrap_or(1);
    let mut lows = [0.0; 3];
    let mut sides = Vec::with_capacity(dimension);
    for k in 0..dimension {
        let name = ["xlo xhi", "ylo yhi", "zlo zhi"][k];
        let (lo, hi) =
            h.bounds[k].ok_or_else(|| ("header".to_string(), format!("no `lo hi {name}` line")))?;
        lows[k] = lo;
        sides.push(hi - lo);
    }
    let mut atoms: Option<Vec<(u64, usize)>> = None;
    let mut c = Configuration {
        dimension,
        sides,
        positions: Vec::new(),
        velocities: None,
        diameters: None,
        masses: None,
        species: None,
        spins: None,
        time: None,
    };
    while i < lines.len() {
        if !is_section(lines[i]) {
            i += 1;
            continue;
        }
        let at = format!("line {}", i + 1);
        let mut parts = lines[i].splitn(2, '#');
        let name = parts.next().unwrap_or("").trim();
        let style = parts.next().map(str::trim).unwrap_or("");
        match name {
            "Atoms" => {
                if !style.is_empty() && style != "sphere" {
                    return Err((
                        at,
                        format!(
                            "atom style `{style}`; allowed: sphere (atom-ID atom-type diameter \
                             density x y z)"
                        ),
                    ));
                }
                if atoms.is_some() {
                    return Err((at, "a second Atoms section".into()));
                }
                let (list, next) = rows(&lines, i, n, "Atoms")?;
                atoms = Some(read_atoms(&list, &mut c, &lows, types)?);
                i = next;
            }
            "Velocities" => {
                let Some(ids) = &atoms else {
                    return Err((
                        at,
                        "Velocities before Atoms; LAMMPS wants Atoms first".into(),
                    ));
                };
                if c.velocities.is_some() {
                    return Err((at, "a second Velocities section".into()));
                }
                let (list, next) = rows(&lines, i, n, "Velocities")?;
                read_velocities(&list, &mut c, ids)?;
                i = next;
            }
            _ => i += 1,
        }
    }
    let Some(ids) = atoms else {
        return Err(("file".into(), "no Atoms section".into()));
    };
    let order: Vec<usize> = ids.iter().map(|(_, r)| *r).collect();
    // Atoms and velocities are in file order: by id.
    Ok(super::lammps::permuted(c, &order))
}

/// The atoms' lines into `c` (in file order); returns (id, row) sorted by id.
fn read_atoms(
    list: &Rows<'_>,
    c: &mut Configuration,
    lows: &[f64; 3],
    types: usize,
) -> Result<Vec<(u64, usize)>, Fault> {
    let d = c.dimension;
    let n = list.len();
    let (mut diameters, mut masses, mut species) = (
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    );
    let mut ids = Vec::with_capacity(n);
    for (row, (i, words)) in list.iter().enumerate() {
        let line = i + 1;
        let at = || format!("line {line}");
        if words.len() != 7 && words.len() != 10 {
            return Err((
                at(),
                format!(
                    "{} values; allowed: 7 (atom-ID atom-type diameter density x y z) or 10 \
                     (and image flags ix iy iz)",
                    words.len()
                ),
            ));
        }
        let id = words[0]
            .parse::<u64>()
            .ok()
            .filter(|id| *id >= 1)
            .ok_or_else(|| {
                (
                    at(),
                    format!(
                        "column `atom-ID`: `{}` is not an atom id (1, 2, ...)",
                        words[0]
                    ),
                )
            })?;
        let kind = words[1]
            .parse::<usize>()
            .ok()
            .filter(|t| (1..=types).contains(t))
            .ok_or_else(|| {
                (
                    at(),
                    format!(
                        "column `atom-type`: `{}`; allowed: 1 ..= {types} (`atom types`)",
                        words[1]
                    ),
                )
            })?;
        let diameter = number(words[2], line, "diameter")?;
        let rho = number(words[3], line, "density")?;
        if !(rho.is_finite() && rho > 0.0) {
            return Err((
                at(),
                format!("column `density`: {rho} is not a finite number > 0"),
            ));
        }
        let mut p = [0.0; 3];
        for k in 0..d {
            let l = c.sides[k];
            let x = number(words[4 + k], line, ["x", "y", "z"][k])? - lows[k];
            // read_data remaps atoms into a periodic box.
            p[k] = if x.is_finite() && !(0.0..l).contains(&x) {
                let w = x - l * (x / l).floor();
                if w >= l || !w.is_finite() {
                    0.0
                } else {
                    w
                }
            } else {
                x
            };
        }
        if words.len() == 10 {
            for (k, w) in words[7..].iter().enumerate() {
                if w.parse::<i64>().is_err() {
                    return Err((
                        at(),
                        format!(
                            "column `{}`: `{w}` is not an image flag (an integer)",
                            ["ix", "iy", "iz"][k]
                        ),
                    ));
                }
            }
        }
        c.positions.push(p);
        diameters.push(diameter);
        masses.push(mass(diameter, rho));
        species.push(kind - 1);
        ids.push((id, row));
    }
    c.diameters = Some(diameters);
    c.masses = Some(masses);
    c.species = Some(species);
    ids.sort_unstable();
    if let Some(w) = ids.windows(2).find(|w| w[0].0 == w[1].0) {
        return Err((
            format!("line {}", list[w[1].1].0 + 1),
            format!("column `atom-ID`: atom id {} appears twice", w[0].0),
        ));
    }
    Ok(ids)
}

/// The velocities' lines into `c`, at the file-order row of each atom id (`ids` sorted).
fn read_velocities(
    list: &Rows<'_>,
    c: &mut Configuration,
    ids: &[(u64, usize)],
) -> Result<(), Fault> {
    let d = c.dimension;
    let n = ids.len();
    let mut v: Vec<Option<Vec3>> = vec![None; n];
    let mut w = vec![[0.0; 3]; n];
    for (i, words) in list {
        let line = i + 1;
        let at = || format!("line {line}");
        if words.len() != 7 {
            return Err((
                at(),
                format!(
                    "{} values; allowed: 7 (atom-ID vx vy vz omegax omegay omegaz)",
                    words.len()
                ),
            ));
        }
        let id = words[0].parse::<u64>().map_err(|_| {
            (
                at(),
                format!("column `atom-ID`: `{}` is not an atom id", words[0]),
            )
        })?;
        let rank = ids.binary_search_by_key(&id, |(id, _)| *id).map_err(|_| {
            (
                at(),
                format!("column `atom-ID`: atom id {id} is not in the Atoms section"),
            )
        })?;
        let row = ids[rank].1;
        if v[row].is_some() {
            return Err((
                at(),
                format!("column `atom-ID`: atom id {id} appears twice"),
            ));
        }
        let mut velocity = [0.0; 3];
        for k in 0..d {
            velocity[k] = number(words[1 + k], line, ["vx", "vy", "vz"][k])?;
        }
        let mut spin = [0.0; 3];
        // Disks turn about z alone.
        let axes = if d == 2 { 2..3 } else { 0..3 };
        for k in axes {
            spin[k] = number(words[4 + k], line, ["omegax", "omegay", "omegaz"][k])?;
        }
        v[row] = Some(velocity);
        w[row] = spin;
    }
    c.velocities = Some(v.into_iter().map(|x| x.unwrap_or_default()).collect());
    c.spins = Some(w);
    Ok(())
}

/// A data file of `atom_style sphere` that `read_data` reads: the box from 0 (2D: z bounds
/// -0.5 0.5, z = 0, as LAMMPS' `dimension 2`), `Atoms # sphere` (diameter 1 where the
/// configuration has none, the density of mass 1 where it has no masses, type = species +
/// 1), and `Velocities` when there are velocities or spins (0 for what is missing).
pub(super) fn write_data(out: &mut dyn Write, c: &Configuration) -> io::Result<()> {
    let d = c.dimension;
    let types = c
        .species
        .as_ref()
        .and_then(|s| s.iter().max())
        .map_or(1, |m| m + 1);
    writeln!(
        out,
        "LAMMPS data file (atom_style sphere) written by haff\n"
    )?;
    writeln!(out, "{} atoms\n{types} atom types\n", c.len())?;
    for (k, name) in ["xlo xhi", "ylo yhi", "zlo zhi"].iter().enumerate() {
        if k < d {
            writeln!(out, "0 {} {name}", output::number(c.sides[k]))?;
        } else {
            writeln!(out, "-0.5 0.5 {name}")?;
        }
    }
    writeln!(out, "\nAtoms # sphere\n")?;
    let mut row = String::new();
    for i in 0..c.len() {
        row.clear();
        let kind = c.species.as_ref().map_or(1, |s| s[i] + 1);
        let diameter = c.diameter(i);
        let m = c.masses.as_ref().map_or(1.0, |m| m[i]);
        row += &format!(
            "{} {kind} {} {}",
            i + 1,
            output::number(diameter),
            output::number(density(diameter, m))
        );
        for x in c.positions[i] {
            row.push(' ');
            row.push_str(&output::number(x));
        }
        writeln!(out, "{row}")?;
    }
    if c.velocities.is_some() || c.spins.is_some() {
        writeln!(out, "\nVelocities\n")?;
        for i in 0..c.len() {
            row.clear();
            row += &(i + 1).to_string();
            let v = c.velocities.as_ref().map_or([0.0; 3], |v| v[i]);
            let w = c.spins.as_ref().map_or([0.0; 3], |w| w[i]);
            for x in v.iter().chain(&w) {
                row.push(' ');
                row.push_str(&output::number(*x));
            }
            writeln!(out, "{row}")?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
