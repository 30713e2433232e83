//! The drawing vocabulary every kind's figures share: line styles and layers ([`vocab`]),
//! labels placed clear of each other ([`labels`]), constructions' letters, dimensions and
//! captions ([`construction`]), panels with scale bars ([`panels`]),
//! vector polygons ([`polygon`]) and forces ([`forces`], drawn clear of a sheet's mechanism:
//! [`clear_forces`]), printed sheets ([`sheet`],
//! [`sheet_pages`]), diagrams ([`plot`]) and animations ([`animation`]).

pub mod animation;
pub mod clear_forces;
pub mod construction;
pub mod forces;
pub mod labels;
pub mod panels;
pub mod plot;
pub mod polygon;
pub mod sheet;
pub mod sheet_pages;
pub mod vocab;
