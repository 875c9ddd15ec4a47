//! Where each soil lies: a map from a point of the ground to the soil
//! classes there and their weights. Geometry only: a class is an index the
//! caller gives meaning to (its list of soils).
//!
//! A map is layers, bottom to top:
//! 1. a background class, everywhere (optional when a raster covers what
//!    is needed);
//! 2. a [`ClassRaster`]: in a cell, its four corner nodes' bilinear
//!    weights, merged by class. Over a background, the raster covers its
//!    pixels' footprint: it fades into the background (a smoothstep) from
//!    its outer nodes to half a spacing beyond them. Without one, a point
//!    off the raster takes the nearest edge's classes;
//! 3. [`SoilPatch`]es in order, each alpha-blended over what lies under
//!    it: its weight `w` scales the weights below by `1 − w` and adds `w`
//!    to its class.
//!
//! The weights are continuous in (x, y) wherever every patch has an
//! `edge` > 0 (the runtime blends each soil's wheel forces by them, and an
//! ODE integrator needs a continuous right-hand side). At most four classes
//! are returned: where more overlap, each layer keeps the four heaviest,
//! less the fifth's weight, renormalized, which stays continuous (two
//! classes trading places in the ranking both hold the same weight there).

mod patch;
mod raster;

pub use patch::{PatchShape, SoilPatch};
pub use raster::{ClassFile, ClassRaster, read_class_raster};

use std::sync::Arc;

use super::error::TerrainError;

/// `3t² − 2t³` on [0, 1], clamped outside: C1, 0 → 1.
#[inline]
fn smoothstep(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Up to four soil classes and their weights at a point (weights > 0,
/// summing to 1, classes ascending, no repeats; the slots past `count`
/// are unused).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SoilWeights {
    /// The classes, ascending.
    pub classes: [u16; 4],
    /// Their weights.
    pub weights: [f64; 4],
    /// How many slots are used (1 … 4).
    pub count: usize,
}

impl SoilWeights {
    /// One class, all the weight.
    pub fn single(class: u16) -> Self {
        SoilWeights {
            classes: [class, 0, 0, 0],
            weights: [1.0, 0.0, 0.0, 0.0],
            count: 1,
        }
    }

    /// The classes and their weights.
    pub fn iter(&self) -> impl Iterator<Item = (u16, f64)> + '_ {
        self.classes
            .iter()
            .copied()
            .zip(self.weights.iter().copied())
            .take(self.count)
    }
}

/// The classes being composed at a point: the four of the layers below,
/// and one layer's (up to four) on top of them, before the reduction.
struct Mix {
    classes: [u16; 8],
    weights: [f64; 8],
    count: usize,
}

impl Mix {
    const EMPTY: Mix = Mix {
        classes: [0; 8],
        weights: [0.0; 8],
        count: 0,
    };

    /// Adds `w` to `class`, merging a class already there.
    #[inline]
    fn add(&mut self, class: u16, w: f64) {
        for k in 0..self.count {
            if self.classes[k] == class {
                self.weights[k] += w;
                return;
            }
        }
        if self.count < 8 {
            self.classes[self.count] = class;
            self.weights[self.count] = w;
            self.count += 1;
        }
    }

    /// Lays `layer` (classes and weights summing to 1) over the mix with
    /// opacity `alpha` in (0, 1].
    #[inline]
    fn compose(&mut self, layer: &[(u16, f64)], alpha: f64) {
        if alpha >= 1.0 {
            self.count = 0;
        } else {
            let keep = 1.0 - alpha;
            let mut n = 0;
            for k in 0..self.count {
                let w = self.weights[k] * keep;
                if w > 0.0 {
                    self.classes[n] = self.classes[k];
                    self.weights[n] = w;
                    n += 1;
                }
            }
            self.count = n;
        }
        for &(class, w) in layer {
            let w = alpha * w;
            if w > 0.0 {
                self.add(class, w);
            }
        }
        if self.count > 4 {
            self.reduce();
        }
    }

    /// Keeps the four heaviest classes, each less the fifth's weight
    /// (continuous where a class enters or leaves the four), renormalized.
    fn reduce(&mut self) {
        // Insertion sort by weight, heaviest first (at most 8 entries).
        for k in 1..self.count {
            let mut m = k;
            while m > 0 && self.weights[m - 1] < self.weights[m] {
                self.weights.swap(m - 1, m);
                self.classes.swap(m - 1, m);
                m -= 1;
            }
        }
        let fifth = self.weights[4];
        let excess: f64 = self.weights[..4].iter().map(|w| w - fifth).sum();
        if excess > 0.0 {
            let mut n = 0;
            for k in 0..4 {
                let w = (self.weights[k] - fifth) / excess;
                if w > 0.0 {
                    self.classes[n] = self.classes[k];
                    self.weights[n] = w;
                    n += 1;
                }
            }
            self.count = n;
        } else {
            // Five or more equal heaviest: the first four, equally (the
            // one point where the weights may jump).
            self.count = 4;
            self.weights[..4].fill(0.25);
        }
    }

    /// The weights, renormalized, classes ascending.
    #[inline]
    fn finish(mut self, fallback: u16) -> SoilWeights {
        if self.count > 4 {
            self.reduce();
        }
        let total: f64 = self.weights[..self.count].iter().sum();
        if self.count == 0 || total.is_nan() || total <= 0.0 {
            return SoilWeights::single(fallback);
        }
        let mut out = SoilWeights {
            classes: [0; 4],
            weights: [0.0; 4],
            count: self.count,
        };
        for k in 0..self.count {
            let mut m = k;
            let (class, w) = (self.classes[k], self.weights[k] / total);
            while m > 0 && out.classes[m - 1] > class {
                out.classes[m] = out.classes[m - 1];
                out.weights[m] = out.weights[m - 1];
                m -= 1;
            }
            out.classes[m] = class;
            out.weights[m] = w;
        }
        out
    }
}

/// Where each soil class lies (see the module's documentation). Cloning is
/// cheap: the raster and the patches are shared.
#[derive(Clone, Debug, PartialEq)]
pub struct SoilMap {
    background: Option<u16>,
    raster: Option<ClassRaster>,
    patches: Arc<[SoilPatch]>,
    /// Every class the map can return, ascending.
    classes: Vec<u16>,
    /// The class of a point the map cannot place (a non-finite one).
    fallback: u16,
}

impl SoilMap {
    /// One class everywhere.
    pub fn uniform(class: u16) -> Self {
        SoilMap {
            background: Some(class),
            raster: None,
            patches: Arc::new([]),
            classes: vec![class],
            fallback: class,
        }
    }

    /// A map of a `background` class, a `raster` over it, and `patches`
    /// over both in order; at least one of `background` and `raster`
    /// (patches lie over a soil).
    pub fn new(
        background: Option<u16>,
        raster: Option<ClassRaster>,
        patches: Vec<SoilPatch>,
    ) -> Result<SoilMap, TerrainError> {
        let fallback = match (background, &raster) {
            (Some(b), _) => b,
            (None, Some(r)) => r.nodes().first().copied().unwrap_or(0),
            (None, None) => {
                return Err(TerrainError::parameter(
                    "soil",
                    "the soil map has neither a background soil nor a raster of classes: \
                     the patches lie over nothing",
                    "give the ground a soil under the patches (`soil` in [terrain]) or a \
                     soil map",
                ));
            }
        };
        let mut classes: Vec<u16> = background.into_iter().collect();
        if let Some(r) = &raster {
            classes.extend(r.classes());
        }
        classes.extend(patches.iter().map(SoilPatch::class));
        classes.sort_unstable();
        classes.dedup();
        Ok(SoilMap {
            background,
            raster,
            patches: patches.into(),
            classes,
            fallback,
        })
    }

    /// The background class, if any.
    pub fn background(&self) -> Option<u16> {
        self.background
    }

    /// The raster, if any.
    pub fn raster(&self) -> Option<&ClassRaster> {
        self.raster.as_ref()
    }

    /// The patches, bottom to top.
    pub fn patches(&self) -> &[SoilPatch] {
        &self.patches
    }

    /// The soils at (x, y): allocation-free, a few tens of ns per patch
    /// whose bounding box holds the point (the others cost four
    /// comparisons); called per wheel per right-hand side. A non-finite
    /// point gets the background (or the raster's first node) alone.
    pub fn weights(&self, x: f64, y: f64) -> SoilWeights {
        if !(x.is_finite() && y.is_finite()) {
            return SoilWeights::single(self.fallback);
        }
        if self.raster.is_none()
            && self.patches.is_empty()
            && let Some(b) = self.background
        {
            return SoilWeights::single(b);
        }
        let mut mix = Mix::EMPTY;
        if let Some(b) = self.background {
            mix.add(b, 1.0);
        }
        if let Some(r) = &self.raster {
            let (corners, beyond) = r.sample(x, y);
            let alpha = if self.background.is_some() {
                1.0 - smoothstep(2.0 * beyond)
            } else {
                1.0
            };
            if alpha > 0.0 {
                mix.compose(&corners, alpha);
            }
        }
        for patch in self.patches.iter() {
            let alpha = patch.alpha(x, y);
            if alpha > 0.0 {
                mix.compose(&[(patch.class(), 1.0)], alpha);
            }
        }
        mix.finish(self.fallback)
    }

    /// Every class the map can return (ascending).
    pub fn classes(&self) -> Vec<u16> {
        self.classes.clone()
    }

    /// Whether the map is one class everywhere.
    pub fn is_uniform(&self) -> Option<u16> {
        match self.classes.as_slice() {
            [c] => Some(*c),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests;
