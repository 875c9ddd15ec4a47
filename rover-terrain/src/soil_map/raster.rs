//! Rasters of soil classes: a class at each node of a regular grid, placed
//! like a height map, read from a CSV matrix or a grayscale PNG.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::super::csv_grid::{Cells, parse_matrix};
use super::super::error::{FileError, Place, TerrainError};
use super::super::georeference::Georeference;
use super::super::height_field::Bounds;
use super::super::io::read_text;

/// Soil classes at the nodes `(X0 + i·dx, Y0 + j·dy)`, `i = 0 … nx−1`
/// eastward, `j = 0 … ny−1` northward, stored south row first like a
/// [`Grid`](crate::Grid)'s heights. Cloning is cheap: the nodes are shared.
#[derive(Clone, Debug, PartialEq)]
pub struct ClassRaster {
    origin: [f64; 2],
    spacing: [f64; 2],
    /// `[1/dx, 1/dy]`: a query multiplies.
    inverse: [f64; 2],
    nx: usize,
    ny: usize,
    /// `[nx − 1, ny − 1]` as floats.
    last: [f64; 2],
    nodes: Arc<[u16]>,
}

impl ClassRaster {
    /// A raster placed by `georeference` of `nx × ny` (each ≥ 2) `nodes`,
    /// south row first, west to east.
    pub fn new(
        georeference: Georeference,
        nx: usize,
        ny: usize,
        nodes: Vec<u16>,
    ) -> Result<ClassRaster, TerrainError> {
        let g = georeference.check()?;
        if nx < 2 || ny < 2 || nx.checked_mul(ny) != Some(nodes.len()) {
            return Err(TerrainError::parameter(
                "soil_map",
                format!(
                    "{nx} × {ny} nodes with {} classes: a soil map needs at least 2 × 2 nodes \
                     and one class per node",
                    nodes.len()
                ),
                "give one class per node, south row first, west to east",
            ));
        }
        Ok(ClassRaster {
            origin: g.origin,
            spacing: g.spacing,
            inverse: [1.0 / g.spacing[0], 1.0 / g.spacing[1]],
            nx,
            ny,
            last: [(nx - 1) as f64, (ny - 1) as f64],
            nodes: nodes.into(),
        })
    }

    /// Where the raster lies.
    pub fn georeference(&self) -> Georeference {
        Georeference {
            origin: self.origin,
            spacing: self.spacing,
        }
    }

    /// Nodes west to east.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Nodes south to north.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// The class of node (i, j).
    pub fn class(&self, i: usize, j: usize) -> Option<u16> {
        if i < self.nx && j < self.ny {
            self.nodes.get(j * self.nx + i).copied()
        } else {
            None
        }
    }

    /// The classes of the nodes, south row first.
    pub fn nodes(&self) -> &[u16] {
        &self.nodes
    }

    /// Every class of the raster, ascending.
    pub fn classes(&self) -> Vec<u16> {
        let mut seen = vec![0u64; 1024];
        for &c in self.nodes.iter() {
            seen[usize::from(c) / 64] |= 1 << (c % 64);
        }
        (0..=u16::MAX)
            .filter(|&c| seen[usize::from(c) / 64] & (1 << (c % 64)) != 0)
            .collect()
    }

    /// The same raster with each class `c` replaced by `f(c)`.
    pub fn map_classes(&self, mut f: impl FnMut(u16) -> u16) -> ClassRaster {
        ClassRaster {
            nodes: self.nodes.iter().map(|&c| f(c)).collect(),
            ..self.clone()
        }
    }

    /// The area the raster's pixels cover: half a spacing beyond its outer
    /// nodes (an image's pixel centres are its nodes).
    pub fn footprint(&self) -> Bounds {
        let [x0, y0] = self.origin;
        let [dx, dy] = self.spacing;
        Bounds {
            x_min: x0 - 0.5 * dx,
            x_max: x0 + (self.last[0] + 0.5) * dx,
            y_min: y0 - 0.5 * dy,
            y_max: y0 + (self.last[1] + 0.5) * dy,
        }
    }

    /// The four corner nodes' classes and bilinear weights at (x, y) (a
    /// point off the nodes' rectangle is clamped onto it), and how far
    /// beyond that rectangle the point lies, in node spacings along the
    /// farther axis (0 on or inside it).
    #[inline]
    pub(super) fn sample(&self, x: f64, y: f64) -> ([(u16, f64); 4], f64) {
        let u = (x - self.origin[0]) * self.inverse[0];
        let v = (y - self.origin[1]) * self.inverse[1];
        let out_u = (-u).max(u - self.last[0]).max(0.0);
        let out_v = (-v).max(v - self.last[1]).max(0.0);
        let u = u.clamp(0.0, self.last[0]);
        let v = v.clamp(0.0, self.last[1]);
        // The last cell holds the east (north) edge: i ≤ nx − 2.
        let i = (u.floor() as usize).min(self.nx - 2);
        let j = (v.floor() as usize).min(self.ny - 2);
        let fu = u - i as f64;
        let fv = v - j as f64;
        let at = |i: usize, j: usize| self.nodes.get(j * self.nx + i).copied().unwrap_or(0);
        (
            [
                (at(i, j), (1.0 - fu) * (1.0 - fv)),
                (at(i + 1, j), fu * (1.0 - fv)),
                (at(i, j + 1), (1.0 - fu) * fv),
                (at(i + 1, j + 1), fu * fv),
            ],
            out_u.max(out_v),
        )
    }
}

/// How a raster file's nodes lie in it, to name a node's place.
#[derive(Clone, Debug, PartialEq)]
enum Layout {
    /// A CSV matrix: row j (south first) on line `lines[j]`.
    Csv { lines: Vec<usize> },
    /// An image: the top row is the north one.
    Png,
}

/// A raster of classes as read from its file: the raster, and where each
/// node is in the file (for messages about a class).
#[derive(Clone, Debug, PartialEq)]
pub struct ClassFile {
    /// The classes, as the file gives them.
    pub raster: ClassRaster,
    path: PathBuf,
    layout: Layout,
}

impl ClassFile {
    /// Node (i, j)'s place in the file: `classes.csv:7: row 3, column 2`
    /// (rows counted as the matrix's, south first) or `classes.png: pixel
    /// (row 1, column 3)` (from the top).
    pub fn place(&self, i: usize, j: usize) -> String {
        let path = self.path.display();
        match &self.layout {
            Layout::Csv { lines } => format!(
                "{path}:{}: row {}, column {}",
                lines.get(j).copied().unwrap_or(0),
                j + 1,
                i + 1
            ),
            Layout::Png => format!(
                "{path}: pixel (row {}, column {})",
                self.raster.ny - j,
                i + 1
            ),
        }
    }

    /// The place of the first node of `class` in the file's reading order.
    pub fn first_place(&self, class: u16) -> Option<String> {
        let r = &self.raster;
        let rows: Box<dyn Iterator<Item = usize>> = match self.layout {
            Layout::Csv { .. } => Box::new(0..r.ny),
            Layout::Png => Box::new((0..r.ny).rev()),
        };
        for j in rows {
            if let Some(i) = (0..r.nx).find(|&i| r.class(i, j) == Some(class)) {
                return Some(self.place(i, j));
            }
        }
        None
    }
}

/// A soil map's cells.
const CLASSES: Cells = Cells {
    noun: "class",
    form: "classes are whole numbers 0 … 65535",
    unit: "",
    table: "[terrain.soil_map]",
};

/// Reads a raster of soil classes: a CSV matrix (`.csv`: its header, or
/// `georeference`, places it) or an 8- or 16-bit grayscale PNG (`.png`,
/// placed by `georeference`), each value a class 0 … 65535.
pub fn read_class_raster(
    path: &Path,
    georeference: Option<Georeference>,
) -> Result<ClassFile, TerrainError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("csv") => read_csv_classes(path, georeference),
        Some("png") => read_png_classes(path, georeference),
        _ => Err(TerrainError::parameter(
            "soil_map.path",
            format!("`{}` is neither a .csv nor a .png file", path.display()),
            "give the soil classes as a CSV matrix (.csv) or a grayscale PNG (.png)",
        )),
    }
}

fn read_csv_classes(
    path: &Path,
    georeference: Option<Georeference>,
) -> Result<ClassFile, TerrainError> {
    let m = parse_matrix(&read_text(path)?, path, georeference, &CLASSES)?;
    let mut nodes = Vec::with_capacity(m.values.len());
    for (k, &v) in m.values.iter().enumerate() {
        if !(v.fract() == 0.0 && (0.0..=65535.0).contains(&v)) {
            let (i, j) = (k % m.nx, k / m.nx);
            return Err(FileError::at(
                path,
                Place::Line(m.lines.get(j).copied().unwrap_or(0)),
                format!(
                    "row {}, column {}: the class {v} is not a whole number 0 … 65535",
                    j + 1,
                    i + 1
                ),
                "a soil map's cells are soil classes, whole numbers each listed in \
                 [terrain.soil_map.classes]",
            ));
        }
        nodes.push(v as u16);
    }
    Ok(ClassFile {
        raster: ClassRaster::new(m.georeference, m.nx, m.ny, nodes)?,
        path: path.to_path_buf(),
        layout: Layout::Csv { lines: m.lines },
    })
}

#[cfg(feature = "png")]
fn read_png_classes(
    path: &Path,
    georeference: Option<Georeference>,
) -> Result<ClassFile, TerrainError> {
    use super::super::png_map::{Samples, decode_samples};
    let Some(georeference) = georeference else {
        return Err(TerrainError::parameter(
            "soil_map.origin",
            "a PNG soil map needs origin and spacing".to_string(),
            "set origin = [x, y] (centre of the bottom-left pixel) and spacing = [dx, dy] in \
             metres in [terrain.soil_map]",
        ));
    };
    let georeference = georeference.check()?;
    let bytes = super::super::io::read_bytes(path)?;
    let image = decode_samples(&bytes, path, Samples::Classes)?;
    Ok(ClassFile {
        raster: ClassRaster::new(georeference, image.width, image.height, image.values)?,
        path: path.to_path_buf(),
        layout: Layout::Png,
    })
}

#[cfg(not(feature = "png"))]
fn read_png_classes(_: &Path, _: Option<Georeference>) -> Result<ClassFile, TerrainError> {
    Err(TerrainError::parameter(
        "soil_map.path",
        "this build of rover-terrain reads no PNG images",
        "enable the `png` feature of rover-terrain, or give the classes as a .csv matrix",
    ))
}
