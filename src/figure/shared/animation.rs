//! A mechanism's motion as drawings: what every position shares (the base: ground,
//! paths, panel titles) and what moves (one drawing per position), with the fixed window
//! that every frame shows. The four-bar and the linkage hand their motion over as one
//! [`Animation`]; the writers turn it into one DXF with a layer per position, SVG frames and
//! the HTML viewer, without knowing which mechanism it is.
//!
//! The moving drawings are made on demand ([`Animation::pose`]), in any order and on any
//! thread, so an animation of many positions costs nothing until it is drawn.

use crate::draw::{Bounds, Drawing};
use crate::geom::Point;

/// Draws position `k` of an animation (its moving part only).
pub type PoseFn = Box<dyn Fn(usize) -> Drawing + Send + Sync>;

/// The mechanism at one value of its drive, solved (not drawn): for a drag.
#[derive(Debug, Clone, PartialEq)]
pub struct DriveState {
    /// The position's label (`φ1 = 93.25°`, `t = 0.2731 s`).
    pub label: String,
    /// The named points of the mechanism (`A`, `B`, `crank.A`, ...), model units.
    pub points: Vec<(String, Point)>,
    /// The largest constraint residual, relative to the mechanism's size.
    pub residual: f64,
}

/// Solves the mechanism at drive value `s`, continuing the assembly mode of position `k`;
/// the message says why it cannot be assembled there.
pub type SolveAtFn = Box<dyn Fn(usize, f64) -> Result<DriveState, String> + Send + Sync>;

/// Draws the moving part at drive value `s` (assembly mode of position `k`), at the run's
/// scales.
pub type DrawAtFn = Box<dyn Fn(usize, f64) -> Result<Drawing, String> + Send + Sync>;

/// A motion's drive: the value at every position (the crank angle in degrees, the time in
/// seconds), and the mechanism solved and drawn at any value between.
pub struct Drive {
    /// The drive's value at each position (one per [`Animation::names`]), increasing.
    pub values: Vec<f64>,
    /// Solves at any value.
    pub solve: SolveAtFn,
    /// Draws at any value.
    pub draw: DrawAtFn,
}

/// A motion ready to be drawn.
pub struct Animation {
    /// A title for the viewer (e.g. `fourbar-chebyshev: four-bar, 360 positions`).
    pub title: String,
    /// What every position shares, on its content layers.
    pub base: Drawing,
    /// The model-space window of every frame (so that the picture does not jump); `None`:
    /// fitted to the base and every position ([`Animation::window`]).
    pub fixed_window: Option<Bounds>,
    /// One name per position: its DXF layer (`POS_000`, …); the frame file is the name in
    /// lower case.
    pub names: Vec<String>,
    /// One label per position, shown with the viewer's slider (`φ1 = 90°`, `t = 0.2500 s`).
    pub labels: Vec<String>,
    /// Draws the moving part of position `k` (`k < names.len()`).
    pose: PoseFn,
    /// The drive, for a drag (`None`: the positions only).
    pub drive: Option<Drive>,
}

impl std::fmt::Debug for Animation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Animation")
            .field("title", &self.title)
            .field("window", &self.fixed_window)
            .field("positions", &self.names.len())
            .finish_non_exhaustive()
    }
}

impl Animation {
    /// An animation of `names.len()` positions; `labels` has one label per name and
    /// `pose(k)` draws position `k`'s moving part on the content layers.
    ///
    /// # Panics
    /// When `labels` and `names` differ in length (a bug in the caller, not user input).
    pub fn new(
        title: String,
        base: Drawing,
        fixed_window: Option<Bounds>,
        names: Vec<String>,
        labels: Vec<String>,
        pose: impl Fn(usize) -> Drawing + Send + Sync + 'static,
    ) -> Animation {
        assert_eq!(names.len(), labels.len(), "one label per position");
        Animation { title, base, fixed_window, names, labels, pose: Box::new(pose), drive: None }
    }

    /// The animation with its drive (for a drag).
    pub fn with_drive(mut self, drive: Drive) -> Animation {
        self.drive = Some(drive);
        self
    }

    /// The animation of the positions `keep` (indices into this one's, in the order to
    /// draw them; each less than [`Animation::len`]): their names, labels and drawings,
    /// and the drive at their values (a drag from the `j`-th continues position
    /// `keep[j]`'s assembly mode). The base and the window stay the whole motion's.
    ///
    /// # Panics
    /// When an index is out of range (a bug in the caller: `run::positions` selects from
    /// the run's positions).
    pub fn keep(self, keep: Vec<usize>) -> Animation {
        let Animation { title, base, fixed_window, names, labels, pose, drive } = self;
        let keep = std::sync::Arc::new(keep);
        let names = keep.iter().map(|&k| names[k].clone()).collect();
        let labels = keep.iter().map(|&k| labels[k].clone()).collect();
        let drive = drive.map(|d| {
            let Drive { values, solve, draw } = d;
            let values = keep.iter().map(|&k| values[k]).collect();
            let (ks, kd) = (keep.clone(), keep.clone());
            Drive { values, solve: Box::new(move |j, s| solve(ks[j], s)), draw: Box::new(move |j, s| draw(kd[j], s)) }
        });
        let pose: PoseFn = Box::new(move |j| pose(keep[j]));
        Animation { title, base, fixed_window, names, labels, pose, drive }
    }

    /// Number of positions.
    pub fn len(&self) -> usize {
        self.names.len()
    }

    /// Whether there is no position to draw.
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }

    /// The moving part of position `k`.
    pub fn pose(&self, k: usize) -> Drawing {
        (self.pose)(k)
    }

    /// The window of every frame: the fixed one, or the bounds of the base and of `poses`
    /// (every position's moving part, [`Animation::poses`]); a unit square for an empty
    /// drawing.
    pub fn window(&self, poses: &[Drawing]) -> Bounds {
        if let Some(w) = self.fixed_window {
            return w;
        }
        let all = std::iter::once(&self.base).chain(poses).filter_map(Drawing::bounds);
        all.reduce(|a, b| Bounds {
            min: Point::new(a.min.x.min(b.min.x), a.min.y.min(b.min.y)),
            max: Point::new(a.max.x.max(b.max.x), a.max.y.max(b.max.y)),
        })
        .unwrap_or(Bounds { min: Point::new(0.0, 0.0), max: Point::new(1.0, 1.0) })
    }

    /// One frame: the base with `pose` (a result of [`Animation::pose`]) on top.
    pub fn frame_of(&self, pose: &Drawing) -> Drawing {
        let mut d = self.base.clone();
        d.append(pose);
        d
    }

    /// Every position's moving part, drawn in parallel.
    pub fn poses(&self) -> Vec<Drawing> {
        use crate::par::prelude::*;
        (0..self.len()).into_par_iter().map(|k| self.pose(k)).collect()
    }

    /// The whole motion in one drawing: [`Animation::all_positions`] of [`Animation::poses`].
    pub fn whole(&self) -> Drawing {
        self.all_positions(&self.poses())
    }

    /// The whole motion in one drawing (for the DXF): the base on its content layers and
    /// each position on its own layer ([`Animation::names`]), every entity keeping its
    /// colour and line type. `poses[k]` is position `k`'s moving part. The first position's
    /// layer is on and every other position's off ([`crate::draw::Layer::on`]), so that the
    /// file opens as one drawing of the mechanism (the base and position 0) and the user
    /// switches positions on and off in the layer manager.
    pub fn all_positions(&self, poses: &[Drawing]) -> Drawing {
        let mut d = self.base.clone();
        for (k, (name, pose)) in self.names.iter().zip(poses).enumerate() {
            d.append_on_layer(pose, name);
            if k > 0 {
                d.set_layer_on(name, false);
            }
        }
        d
    }
}
