//! The parameters of an `N`-joint arm: names, units and their place in the parameter vector.

/// What a parameter is measured in (in the files and every output).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unit {
    /// Millimetres.
    Mm,
    /// Degrees (radians inside the model).
    Deg,
}

impl Unit {
    /// `mm` or `°`.
    pub fn symbol(self) -> &'static str {
        match self {
            Unit::Mm => "mm",
            Unit::Deg => "°",
        }
    }
}

/// The five parameters of a joint, in order.
pub const JOINT_PARAMETERS: [(&str, Unit); 5] = [
    ("theta", Unit::Deg),
    ("d", Unit::Mm),
    ("a", Unit::Mm),
    ("alpha", Unit::Deg),
    ("beta", Unit::Deg),
];

/// The base parameters, in order.
pub const BASE_PARAMETERS: [(&str, Unit); 6] = [
    ("base_x", Unit::Mm),
    ("base_y", Unit::Mm),
    ("base_z", Unit::Mm),
    ("base_rx", Unit::Deg),
    ("base_ry", Unit::Deg),
    ("base_rz", Unit::Deg),
];

/// The tool parameters, in order.
pub const TOOL_PARAMETERS: [(&str, Unit); 3] = [
    ("tool_x", Unit::Mm),
    ("tool_y", Unit::Mm),
    ("tool_z", Unit::Mm),
];

/// The tool frame's rotation, after the tool point: parameters of 6-DoF measurements only
/// ([`crate::pose`]).
pub const TOOL_ROTATION_PARAMETERS: [(&str, Unit); 3] = [
    ("tool_rx", Unit::Deg),
    ("tool_ry", Unit::Deg),
    ("tool_rz", Unit::Deg),
];

/// The number of parameters of an arm with `joints` joints: `5N + 9`.
pub fn count(joints: usize) -> usize {
    5 * joints + BASE_PARAMETERS.len() + TOOL_PARAMETERS.len()
}

/// Names and units of every parameter of an arm with `joints` joints, in model order:
/// `theta1, d1, a1, alpha1, beta1, …, base_x, …, base_rz, tool_x, tool_y, tool_z`.
pub fn names(joints: usize) -> Vec<(String, Unit)> {
    let mut out = Vec::with_capacity(count(joints));
    for i in 1..=joints {
        out.extend(
            JOINT_PARAMETERS
                .iter()
                .map(|(n, u)| (format!("{n}{i}"), *u)),
        );
    }
    out.extend(BASE_PARAMETERS.iter().map(|(n, u)| (n.to_string(), *u)));
    out.extend(TOOL_PARAMETERS.iter().map(|(n, u)| (n.to_string(), *u)));
    out
}

/// Names and units of every parameter of an arm with `joints` joints measured by a 6-DoF probe:
/// [`names`], then `tool_rx, tool_ry, tool_rz`.
pub fn pose_names(joints: usize) -> Vec<(String, Unit)> {
    let mut out = names(joints);
    out.extend(
        TOOL_ROTATION_PARAMETERS
            .iter()
            .map(|(n, u)| (n.to_string(), *u)),
    );
    out
}

/// The unit of the parameter called `name` (`theta3`, `base_rx`, `tool_rz`, …), as [`names`] and
/// [`pose_names`] give it; `None` for a name no arm has.
pub fn unit_of(name: &str) -> Option<Unit> {
    let stem = name.trim_end_matches(|c: char| c.is_ascii_digit());
    let joint = stem.len() < name.len();
    let table: &[(&str, Unit)] = if joint {
        &JOINT_PARAMETERS
    } else {
        &[
            BASE_PARAMETERS.as_slice(),
            &TOOL_PARAMETERS,
            &TOOL_ROTATION_PARAMETERS,
        ]
        .concat()
    };
    table.iter().find(|(n, _)| *n == stem).map(|(_, u)| *u)
}
