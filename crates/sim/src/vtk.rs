//! VTK XML files for ParaView (through `vtkio`): the particles of a snapshot as an
//! unstructured grid of vertex cells (`.vtu`), coarse-grained fields as image data (`.vti`),
//! and the `.pvd` collection that makes a time series of either. 1D and 2D data are placed
//! in the z = 0 plane (and y = 0 line).

use crate::error::{Error, Result};
use gas::structure::Fields;
use gas::system::System;
use std::fmt::Write as _;
use std::path::Path;
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, Extent, ImageDataPiece, Piece,
    UnstructuredGridPiece, Version, VertexNumbers, Vtk,
};

/// Per-particle data of a snapshot beyond the state.
pub struct ParticleData<'a> {
    /// Collisions of each particle (event-driven engine), if known.
    pub collisions: Option<&'a [u64]>,
    /// Species index of each particle (order of `system.species`; 0 without a mixture).
    pub species: &'a [u32],
    /// Bath temperature of each particle (stochastic law).
    pub bath_temperatures: Option<&'a [f64]>,
    /// Angular velocity of each particle (rough particles; disks about z).
    pub angular_velocities: Option<&'a [[f64; 3]]>,
}

fn padded<const D: usize>(v: &[f64; D]) -> [f64; 3] {
    std::array::from_fn(|a| if a < D { v[a] } else { 0.0 })
}

fn export(vtk: Vtk, path: &Path) -> Result<()> {
    vtk.export(path).map_err(|e| Error::Write {
        path: path.to_path_buf(),
        source: std::io::Error::other(e.to_string()),
    })
}

/// The name of the field data array of a snapshot's `.vtu` that holds the box's sides
/// (one per dimension, ascii, the shortest decimal form that reads back to the same f64).
pub const BOX_ARRAY: &str = "box";

/// The arrays of a `.vtu` of particles, three components per point and vector; the
/// optional ones are written when given, in this order.
pub(crate) struct VtuParticles {
    /// The box's sides (one per dimension), written as field data [`BOX_ARRAY`].
    pub sides: Vec<f64>,
    pub points: Vec<f64>,
    pub radii: Vec<f64>,
    pub masses: Option<Vec<f64>>,
    pub velocities: Option<Vec<f64>>,
    pub species: Option<Vec<u32>>,
    pub collisions: Option<Vec<u64>>,
    pub bath_temperatures: Option<Vec<f64>>,
    pub angular_velocities: Option<Vec<f64>>,
}

/// Writes the particles of `system` as `path` (`.vtu`): points at the centres, one vertex
/// cell each, with the point data radius, velocity, mass, species and (when known)
/// collisions, bath_temperature and angular_velocity, and the box as field data.
pub fn write_particles<const D: usize>(
    path: &Path,
    system: &System<D>,
    data: &ParticleData<'_>,
) -> Result<()> {
    write_vtu(
        path,
        VtuParticles {
            sides: system.sides.to_vec(),
            points: system.positions.iter().flat_map(padded).collect(),
            radii: system.radii.clone(),
            masses: Some(system.masses.clone()),
            velocities: Some(system.velocities.iter().flat_map(padded).collect()),
            species: Some(data.species.to_vec()),
            collisions: data.collisions.map(<[u64]>::to_vec),
            bath_temperatures: data.bath_temperatures.map(<[f64]>::to_vec),
            angular_velocities: data
                .angular_velocities
                .map(|w| w.iter().flatten().copied().collect()),
        },
    )
}

/// Writes `particles` as `path` (`.vtu`, VTK XML through `vtkio`, binary f64 arrays;
/// atomically).
/// `vtkio` writes no field data: the box is put in as the first child of
/// `<UnstructuredGrid>`, where VTK's readers (ParaView's) look for a data set's field data.
pub(crate) fn write_vtu(path: &Path, particles: VtuParticles) -> Result<()> {
    let n = particles.radii.len();
    let mut point = vec![Attribute::scalars("radius", 1).with_data(particles.radii)];
    if let Some(m) = particles.masses {
        point.push(Attribute::scalars("mass", 1).with_data(m));
    }
    if let Some(v) = particles.velocities {
        point.push(Attribute::vectors("velocity").with_data(v));
    }
    if let Some(s) = particles.species {
        point.push(Attribute::scalars("species", 1).with_data(s));
    }
    if let Some(c) = particles.collisions {
        point.push(Attribute::scalars("collisions", 1).with_data(c));
    }
    if let Some(b) = particles.bath_temperatures {
        point.push(Attribute::scalars("bath_temperature", 1).with_data(b));
    }
    if let Some(w) = particles.angular_velocities {
        point.push(Attribute::vectors("angular_velocity").with_data(w));
    }
    let piece = UnstructuredGridPiece {
        points: particles.points.into(),
        cells: Cells {
            cell_verts: VertexNumbers::XML {
                connectivity: (0..n as u64).collect(),
                offsets: (1..=n as u64).collect(),
            },
            types: vec![CellType::Vertex; n],
        },
        data: Attributes {
            point,
            cell: vec![],
        },
    };
    let vtk = Vtk {
        version: Version::new((1, 0)),
        title: String::from("haff snapshot"),
        byte_order: ByteOrder::LittleEndian,
        data: DataSet::UnstructuredGrid {
            meta: None,
            pieces: vec![Piece::Inline(Box::new(piece))],
        },
        file_path: None,
    };
    let fail = |message: String| Error::Write {
        path: path.to_path_buf(),
        source: std::io::Error::other(message),
    };
    let mut xml = Vec::new();
    vtk.write_xml(&mut xml).map_err(|e| fail(e.to_string()))?;
    let grid = b"<UnstructuredGrid>";
    let at = xml
        .windows(grid.len())
        .position(|w| w == grid)
        .ok_or_else(|| fail("vtkio wrote no <UnstructuredGrid>".into()))?
        + grid.len();
    let sides: Vec<String> = particles
        .sides
        .iter()
        .map(|&l| crate::output::number(l))
        .collect();
    let field = format!(
        "<FieldData><DataArray type=\"Float64\" Name=\"{BOX_ARRAY}\" NumberOfTuples=\"{}\" \
         format=\"ascii\">{}</DataArray></FieldData>",
        sides.len(),
        sides.join(" ")
    );
    xml.splice(at..at, field.into_bytes());
    crate::output::write_file(path, |out| out.write_all(&xml))
}

/// Writes coarse-grained fields as `path` (`.vti`): G^D cells of sides `spacing` from the
/// origin, with the cell data density, velocity, temperature and vorticity.
pub fn write_fields<const D: usize>(path: &Path, fields: &Fields<D>) -> Result<()> {
    let g = fields.grid as i32;
    let top = |a: usize| if a < D { g } else { 0 };
    let extent = Extent::Ranges([0..=top(0), 0..=top(1), 0..=top(2)]);
    let velocity: Vec<f64> = fields.velocity.iter().flat_map(padded).collect();
    let vorticity: Vec<f64> = fields.vorticity.iter().flatten().copied().collect();
    let cell = vec![
        Attribute::scalars("density", 1).with_data(fields.density.clone()),
        Attribute::vectors("velocity").with_data(velocity),
        Attribute::scalars("temperature", 1).with_data(fields.temperature.clone()),
        Attribute::vectors("vorticity").with_data(vorticity),
    ];
    // Axes beyond the dimension take the first one's spacing (one cell thick).
    let h: [f32; 3] = std::array::from_fn(|a| fields.spacing[if a < D { a } else { 0 }] as f32);
    export(
        Vtk {
            version: Version::new((1, 0)),
            title: String::from("haff fields"),
            byte_order: ByteOrder::LittleEndian,
            data: DataSet::ImageData {
                extent: extent.clone(),
                origin: [0.0; 3],
                spacing: h,
                meta: None,
                pieces: vec![Piece::Inline(Box::new(ImageDataPiece {
                    extent,
                    data: Attributes {
                        point: vec![],
                        cell,
                    },
                }))],
            },
            file_path: None,
        },
        path,
    )
}

/// Writes the ParaView collection `path` (`.pvd`) of `files` (relative names) at their
/// times: a small fixed XML format that `vtkio` does not cover.
pub fn write_collection(path: &Path, files: &[(f64, String)]) -> Result<()> {
    let mut xml = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n",
    );
    for (time, file) in files {
        let _ = writeln!(
            xml,
            "    <DataSet timestep=\"{}\" part=\"0\" file=\"{}\"/>",
            crate::output::number(*time),
            file
        );
    }
    xml.push_str("  </Collection>\n</VTKFile>\n");
    crate::output::write_file(path, |out| out.write_all(xml.as_bytes()))
}
