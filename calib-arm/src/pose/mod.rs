//! Six-degree-of-freedom measurements: a tracker's probe that measures the orientation of the
//! tool frame as well as its position (Leica's T-Mac, a 6-DoF probe), six equations per
//! configuration instead of three ([`model`]).

pub mod model;
pub mod orientation;

pub use model::Arm7Pose;
