//! Command-line flags (clap), and their translation into [`platener::Settings`].

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};
use platener::plan::Material;
use platener::{Settings, Units, Weld};

/// Turns 3D-printing models (STL, OBJ, 3MF) into laser-cut construction plans.
#[derive(Debug, Parser)]
#[command(name = "platener", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Reads a model and reports what platener sees in it: mesh health, welding, planar shapes.
    #[command(
        after_help = "Examples:\n  platener inspect examples/box-3mm.stl\n  platener inspect part.obj --units in --json"
    )]
    Inspect(InspectArgs),
    /// Draws a kerf test strip: cut it, push the spike into the holes, read the kerf of the
    /// hole it fits snugly.
    #[command(
        name = "test-strip",
        after_help = "Examples:\n  platener test-strip -t 3 -o strip.svg\n  platener test-strip -t 4 --material acrylic -o strip.svg"
    )]
    TestStrip(TestStripArgs),
}

/// The sheet material (sets the default kerf the strip marks with `*`).
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum MaterialArg {
    /// Acrylic (PMMA), default kerf 0.15 mm.
    Acrylic,
    /// Plywood, MDF, solid wood, default kerf 0.2 mm.
    Wood,
    /// Cardboard, default kerf 0.3 mm.
    Cardboard,
    /// Paper and thin card, default kerf 0.1 mm.
    Paper,
}

impl MaterialArg {
    /// The library's material.
    pub fn material(self) -> Material {
        match self {
            MaterialArg::Acrylic => Material::Acrylic,
            MaterialArg::Wood => Material::Wood,
            MaterialArg::Cardboard => Material::Cardboard,
            MaterialArg::Paper => Material::Paper,
        }
    }
}

/// `platener test-strip`.
#[derive(Debug, Args)]
pub struct TestStripArgs {
    /// Sheet thickness in mm.
    #[arg(short = 't', long = "thickness")]
    pub thickness: f64,
    /// The material.
    #[arg(long, value_enum, default_value = "wood")]
    pub material: MaterialArg,
    /// Where to write the SVG.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
}

/// The unit of a model file's numbers.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum UnitArg {
    /// Millimetres (default; STL has no unit).
    Mm,
    /// Centimetres.
    Cm,
    /// Inches.
    In,
}

/// Options shared by every command that reads a model.
#[derive(Debug, Args)]
pub struct ModelArgs {
    /// The unit the model's numbers are in.
    #[arg(long, value_enum, default_value = "mm")]
    pub units: UnitArg,
    /// Extra scale factor applied after the unit conversion.
    #[arg(long, default_value_t = 1.0)]
    pub scale: f64,
    /// Weld distance in mm (`auto`: from the model size, at most 2 mm; `0`: exact duplicates only).
    #[arg(long, default_value = "auto")]
    pub weld: String,
    /// Sheet thickness in mm; repeat for several.
    #[arg(short = 't', long = "thickness", default_values_t = [3.0])]
    pub thickness: Vec<f64>,
}

/// `platener inspect`.
#[derive(Debug, Args)]
pub struct InspectArgs {
    /// The model file (.stl, .obj, .3mf).
    pub model: PathBuf,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// Also find the plates (for the thicknesses given with -t) and report which faces became
    /// plates and why the others did not.
    #[arg(long)]
    pub plates: bool,
    /// Find inherent plates only (no extruded plates); implies --plates.
    #[arg(long)]
    pub inherent_only: bool,
    /// Model options.
    #[command(flatten)]
    pub model_args: ModelArgs,
}

impl ModelArgs {
    /// The library settings these flags ask for.
    pub fn settings(&self) -> anyhow::Result<Settings> {
        let weld = match self.weld.trim() {
            "auto" => Weld::Auto,
            s => match s.parse::<f64>() {
                Ok(0.0) => Weld::Off,
                Ok(d) => Weld::Distance(d),
                Err(_) => anyhow::bail!("--weld takes `auto` or a distance in mm, not {s:?}"),
            },
        };
        let settings = Settings {
            units: match self.units {
                UnitArg::Mm => Units::Mm,
                UnitArg::Cm => Units::Cm,
                UnitArg::In => Units::In,
            },
            scale: self.scale,
            weld,
            thicknesses: self.thickness.clone(),
            ..Settings::default()
        };
        settings.validate()?;
        Ok(settings)
    }
}
