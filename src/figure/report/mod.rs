//! The graph-analytical report a student hands in (issue 33): one document of pages on A4
//! or A3 landscape, in paper millimetres, printable at 100 % —
//! 1. the title page ([`title`]): the mechanism, the scene file, the data with units, the
//!    contents, blank fields for the student's name, group and date;
//! 2. the structural analysis ([`structure`]): the mechanism numbered, its driver and Assur
//!    groups drawn apart with class and order, M = 3n − 2p₅ − p₄ worked out;
//! 3. the kinematic diagram ([`kinematic`]) to the standard's symbols at a stated k_l;
//! 4. the plan of positions ([`plan`]) with the paths, the dead positions, the strokes and K;
//! 5. the chosen positions' pages (the printed sheets' figures: the velocity and
//!    acceleration polygons, the force analysis per group, each at its own nice scale);
//! 6. the diagrams over the cycle ([`diagrams`]) with the chosen positions marked.
//!
//! The pages share a frame ([`page`]: border, title block, panels) and tables ([`table`]);
//! the mechanism is drawn from a [`sketch::Sketch`] (the linkage figure with link numbers,
//! the driver and the loads). This module knows no scene: the run builds each page's data.

pub mod compose;
pub mod diagrams;
pub mod freebody;
pub mod kinematic;
pub mod page;
pub mod plan;
pub mod sketch;
pub mod structure;
pub mod table;
pub mod title;
