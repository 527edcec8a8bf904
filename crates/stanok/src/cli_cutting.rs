//! `stanok cutting turn`'s arguments (clap derive).

use clap::{Args, Subcommand, ValueEnum};

#[derive(Debug, Subcommand)]
pub enum CuttingCommand {
    /// Turning (Lab 2): feed, Cv/x/y/m, Kv, cutting speed v, spindle speed n and the machine's n.
    Turn(TurnArgs),
}

/// Work material of `stanok cutting turn` (tables 2.7/2.8 rows).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MaterialArg {
    /// Carbon steel, C < 0.6 % (needs --sigma-b).
    CarbonSteel,
    /// Carbon steel, C > 0.6 % (needs --sigma-b).
    HighCarbonSteel,
    /// Free-machining or chromium steel (needs --sigma-b).
    FreeMachiningSteel,
    /// Chromium-nickel or Cr-Mo-V steel (needs --sigma-b).
    CrNiSteel,
    /// Grey cast iron (needs --hb).
    GreyIron,
    /// Malleable cast iron (needs --hb; the document has no Cv for it).
    MalleableIron,
}

/// Kind of turning.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum OperationArg {
    /// External longitudinal turning.
    Longitudinal,
    /// Facing (cross turning).
    Facing,
    /// Boring.
    Boring,
    /// Parting-off.
    PartingOff,
    /// Grooving.
    Grooving,
    /// Form turning.
    FormTurning,
    /// Thread cutting (the document gives no formula).
    Threading,
}

/// Roughing or finishing, for a single --depth pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PassArg {
    /// Feed from table 2.4.
    Rough,
    /// Feed from table 2.5.
    Finish,
}

/// `stanok cutting turn`.
#[derive(Debug, Clone, Args)]
pub struct TurnArgs {
    /// Work material.
    #[arg(long, value_enum)]
    pub material: MaterialArg,
    /// Ultimate strength of a steel, MPa.
    #[arg(long, value_name = "MPA")]
    pub sigma_b: Option<f64>,
    /// Brinell hardness of a cast iron.
    #[arg(long, value_name = "HB")]
    pub hb: Option<f64>,
    /// Blank surface (K_nv): none, rolled, forging, cu-al, casting, casting-dirty.
    #[arg(long, default_value = "none")]
    pub surface: String,
    /// K_nv inside the surface's range (casting 0.8-0.85, casting-dirty 0.5-0.6); default the
    /// lower bound.
    #[arg(long, value_name = "K")]
    pub surface_factor: Option<f64>,
    /// Tool material grade: T5K10, T14K8, T15K6, T30K4, VK3, VK3M, VK4, VK6, VK6M, VK8, P6M5, P18, KhVG.
    #[arg(long, value_name = "GRADE")]
    pub tool_material: String,
    /// Kind of turning.
    #[arg(long, value_enum, default_value = "longitudinal")]
    pub operation: OperationArg,
    /// Work diameter before the first pass, mm.
    #[arg(long, value_name = "MM")]
    pub diameter: f64,
    /// Depth of cut of one pass, mm.
    #[arg(
        long,
        value_name = "MM",
        required_unless_present = "allowance",
        conflicts_with = "allowance"
    )]
    pub depth: Option<f64>,
    /// Roughing or finishing (with --depth).
    #[arg(long, value_enum, default_value = "rough")]
    pub pass: PassArg,
    /// Allowance per side, mm: split into a rough pass and finish passes (see --split).
    #[arg(long, value_name = "MM")]
    pub allowance: Option<f64>,
    /// Shares of the allowance per pass (0.7,0.3 or 0.7,0.2,0.1).
    #[arg(long, value_delimiter = ',', default_value = "0.7,0.3")]
    pub split: Vec<f64>,
    /// Feed of the (first) pass, mm/rev; default from table 2.4 (the range's lower bound).
    #[arg(long, value_name = "MM_PER_REV")]
    pub feed: Option<f64>,
    /// Feed of the finish passes, mm/rev; default from table 2.5.
    #[arg(long, value_name = "MM_PER_REV")]
    pub finish_feed: Option<f64>,
    /// Required roughness for table 2.5: Ra2.5, Rz20, Rz40, Rz80.
    #[arg(long)]
    pub roughness: Option<String>,
    /// Tool nose radius for table 2.5, mm (0.4, 0.8, 1.2, 1.6, 2.0, 2.4).
    #[arg(long, value_name = "MM")]
    pub nose_radius: Option<f64>,
    /// Tool life T, min (default 60; 120 for form cutters).
    #[arg(long, value_name = "MIN")]
    pub life: Option<f64>,
    /// Lathe centre height for the holder section, mm (16K20: 200).
    #[arg(long, value_name = "MM")]
    pub centre_height: Option<f64>,
    /// The machine's feeds, mm/rev, comma-separated: the feed is corrected down to one of them.
    #[arg(long, value_delimiter = ',', value_name = "LIST")]
    pub machine_feeds: Vec<f64>,
    /// The machine's spindle speeds, rpm, comma-separated: n_act is the largest ≤ n.
    #[arg(long, value_delimiter = ',', value_name = "LIST")]
    pub machine_speeds: Vec<f64>,
    /// Print the calculation as one JSON object.
    #[arg(long)]
    pub json: bool,
}
