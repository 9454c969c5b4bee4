//! The command-line flags every robot's CLI shares, defined once: clap argument groups that
//! `gough` and `arm` flatten into their subcommands (`#[command(flatten)]`). A flag added here
//! appears, with the same name, default, parsing and help, in every command that takes the group.

use crate::OutlierBudget;

/// `--error-scale`'s modes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ErrorScaleMode {
    /// Find the smallest consistent factor.
    Auto,
}

/// `--error-scale`, `--scale-bounds` and `--scale-margin`: find how much error the data need,
/// then certify with it. `B` names the robot's error bounds (its `ScaleBounds`, whose variants'
/// documentation the help lists).
#[derive(clap::Args, Debug, Clone)]
pub struct ErrorScaleArgs<B>
where
    B: clap::ValueEnum + Clone + Send + Sync + 'static,
{
    /// `auto`: first find how much error the data need — the smallest factor by which the
    /// uncertainty file's bounds (--scale-bounds) must be multiplied for the data (a hexapod's:
    /// every leg's) to be consistent, as a proved bracket (s_lo proved inconsistent, s_hi
    /// certified consistent; within 2% where the kernel decides, else the ratio reached and the
    /// first-order minimax estimate are printed; the bracket is in the JSON's `error_scale`) —
    /// then certify at s_hi × --scale-margin. Starts from the first-order minimax fit; a few
    /// certifications of the data's size (per leg on a hexapod).
    #[arg(long, value_name = "auto", value_enum)]
    pub error_scale: Option<ErrorScaleMode>,
    /// With --error-scale: which bounds to scale.
    #[arg(
        long,
        value_name = "WHICH",
        value_parser = clap::builder::EnumValueParser::<B>::new(),
        default_value = "all"
    )]
    pub scale_bounds: B,
    /// With --error-scale: certify at s_hi times this factor (>= 1: a margin over the smallest
    /// consistent bounds).
    // Checked by `crate::error_scale::check_margin` when --error-scale is given.
    #[arg(long, value_name = "F", default_value_t = 1.0)]
    pub scale_margin: f64,
}

/// `--max-outliers`: how many bad configurations a certification tolerates.
#[derive(clap::Args, Debug, Clone)]
pub struct OutlierArgs {
    /// Tolerate up to Q bad configurations (on a hexapod, per leg): the boxes then contain every
    /// parameter vector that fits all but at most Q configurations, and the configurations proved
    /// to be outliers are listed. Costs about C(configurations, Q) certifications (per leg).
    /// `auto`: the smallest Q that is not proved empty (per leg; tries Q = 0, 1, 2, … in turn;
    /// every Q below it is proved too few).
    #[arg(long, value_name = "Q|auto", default_value = "0")]
    pub max_outliers: OutlierBudget,
}
