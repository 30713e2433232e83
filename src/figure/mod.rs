//! Results to drawings: what the engineer draws for each mechanism. Figures build a neutral
//! [`crate::draw::Drawing`]; they never write files.
//!
//! The layout is the architecture: [`shared`] is the drawing vocabulary every kind uses
//! (line styles, labels placed clear of each other, panels, vector polygons, forces,
//! printed sheets, diagrams, animations); each kind's figures live in their own module
//! ([`fourbar`], [`linkage`], [`triad`], [`chain`], [`synthesis`]) and speak that vocabulary.

pub mod chain;
pub mod fourbar;
pub mod linkage;
pub mod report;
pub mod shared;
pub mod synthesis;
pub mod tolerances;
pub mod triad;
