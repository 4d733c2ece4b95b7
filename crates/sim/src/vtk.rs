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

/// Writes the particles of `system` as `path` (`.vtu`): points at the centres, one vertex
/// cell each, with the point data radius, velocity, mass, species and (when known)
/// collisions, bath_temperature and angular_velocity.
pub fn write_particles<const D: usize>(
    path: &Path,
    system: &System<D>,
    data: &ParticleData<'_>,
) -> Result<()> {
    let n = system.len();
    let points: Vec<f64> = system.positions.iter().flat_map(padded).collect();
    let velocities: Vec<f64> = system.velocities.iter().flat_map(padded).collect();
    let mut point = vec![
        Attribute::scalars("radius", 1).with_data(system.radii.clone()),
        Attribute::scalars("mass", 1).with_data(system.masses.clone()),
        Attribute::vectors("velocity").with_data(velocities),
        Attribute::scalars("species", 1).with_data(data.species.to_vec()),
    ];
    if let Some(c) = data.collisions {
        point.push(Attribute::scalars("collisions", 1).with_data(c.to_vec()));
    }
    if let Some(b) = data.bath_temperatures {
        point.push(Attribute::scalars("bath_temperature", 1).with_data(b.to_vec()));
    }
    if let Some(w) = data.angular_velocities {
        let flat: Vec<f64> = w.iter().flatten().copied().collect();
        point.push(Attribute::vectors("angular_velocity").with_data(flat));
    }
    let piece = UnstructuredGridPiece {
        points: points.into(),
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
    export(
        Vtk {
            version: Version::new((1, 0)),
            title: String::from("haff snapshot"),
            byte_order: ByteOrder::LittleEndian,
            data: DataSet::UnstructuredGrid {
                meta: None,
                pieces: vec![Piece::Inline(Box::new(piece))],
            },
            file_path: None,
        },
        path,
    )
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
