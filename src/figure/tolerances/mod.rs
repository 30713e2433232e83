//! Figures of a tolerance study (issue 34): the band drawing (a watched point's nominal path
//! with its tolerance bands, the deviations magnified), each component's band against the
//! motion's abscissa with its widest position marked, and the contributions at that
//! position as a Pareto chart, a triad's tolerance zones in each assembly mode — in the
//! shared vocabulary ([`crate::figure::shared`]).

pub mod band;
pub mod charts;
pub mod zones;

pub use band::{BandPath, band_drawing};
pub use charts::{Bands, Contribution, band_diagram, pareto};
pub use zones::{Zone, ZonePanel, zones_drawing};
