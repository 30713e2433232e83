//! Results to drawings: what the engineer draws for each mechanism. One file per
//! mechanism, plus [`plot`] for diagrams. Figures build a neutral
//! [`crate::draw::Drawing`]; they never write files.

pub mod animation;
pub mod centres;
pub mod chain;
pub mod forces;
pub mod fourbar;
pub mod fourbar_sheet;
pub mod joukowski;
pub mod labels;
pub mod linkage;
pub mod linkage_forces;
pub mod linkage_frame;
pub mod linkage_polygon;
pub mod linkage_sheet;
pub mod panels;
pub mod plot;
pub mod polygon;
pub mod sheet;
pub mod sheet_polygons;
pub mod triad;
pub mod vocab;
