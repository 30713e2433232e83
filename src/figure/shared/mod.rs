//! The drawing vocabulary every kind's figures share: line styles and layers ([`vocab`]),
//! labels placed clear of each other ([`labels`]), panels with scale bars ([`panels`]),
//! vector polygons ([`polygon`]) and forces ([`forces`]), printed sheets ([`sheet`],
//! [`sheet_pages`]), diagrams ([`plot`]) and animations ([`animation`]).

pub mod animation;
pub mod forces;
pub mod labels;
pub mod panels;
pub mod plot;
pub mod polygon;
pub mod sheet;
pub mod sheet_pages;
pub mod vocab;
