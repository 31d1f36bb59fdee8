//! The command line: `raylab render SCENE -o OUT …`, `raylab inspect SCENE --pixel I J …`.

use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// raylab: a ray-tracing viewer and editor built on the course lecture's camera model.
#[derive(Debug, Parser)]
#[command(
    name = "raylab",
    version,
    about,
    args_conflicts_with_subcommands = true
)]
pub struct Cli {
    /// What to do; without a command raylab opens its window.
    #[command(subcommand)]
    pub command: Option<Command>,
    /// The scene to open in the window (default: assets/scenes/seed.xml).
    pub scene: Option<PathBuf>,
    /// A converged linear EXR of the scene at its render size: the window
    /// plots each pass's relative MSE against it as the image refines.
    #[arg(long, value_name = "REF.exr")]
    pub reference: Option<PathBuf>,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a scene to an image without a window (PNG: 8-bit sRGB; EXR: linear float32).
    Render(RenderArgs),
    /// Measure the interactive window's responsiveness without a display.
    Bench(BenchArgs),
    /// Re-trace one sample of one pixel and print its ray tree as JSON.
    Inspect(InspectArgs),
    /// Chart speed against accuracy: error against render time, one line per method (CSV and PNG).
    Chart(ChartArgs),
    /// Join the parts of a split render (`render --crop`, `--samples`) into one EXR.
    Merge(MergeArgs),
    /// Run the suite of cases where numerical methods fail, lecture against robust (table, CSV and PNG).
    Stability(StabilityArgs),
    /// Write the scene's mesh instances as placed in its world (OBJ files and meshes.json), for another renderer.
    ExportMeshes(ExportMeshesArgs),
}

/// Arguments of `raylab merge`.
#[derive(Debug, clap::Args)]
pub struct MergeArgs {
    /// The merged image (.exr).
    pub output: PathBuf,
    /// The parts: EXRs written by `raylab render` with `--crop` or
    /// `--samples`, all of the same scene, camera and size.
    #[arg(required = true, num_args = 1..)]
    pub parts: Vec<PathBuf>,
}

/// Arguments of `raylab export-meshes`.
#[derive(Debug, clap::Args)]
pub struct ExportMeshesArgs {
    /// The scene file.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The directory to write meshK.obj and meshes.json into (created if needed).
    #[arg(long)]
    pub dir: PathBuf,
}

/// Arguments of `raylab stability`.
#[derive(Debug, clap::Args)]
pub struct StabilityArgs {
    /// Fewer tests per row (2,000 rays instead of 100,000): seconds instead of a minute.
    #[arg(long)]
    pub quick: bool,
    /// Where to write: OUTPUT.csv and OUTPUT.png (replaced if they exist).
    /// Without it: stability.csv and stability.png, or stability-2.csv and
    /// stability-2.png, … — the first pair not yet taken.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// Arguments of `raylab chart`.
#[derive(Debug, clap::Args)]
pub struct ChartArgs {
    /// The scene file.
    pub scene: PathBuf,
    /// A converged linear EXR of the scene at its own size; without one,
    /// raylab path-traces its own reference for 4 × `--seconds` first.
    #[arg(long, value_name = "REF.exr")]
    pub reference: Option<PathBuf>,
    /// The methods to compare, comma-separated.
    #[arg(long, value_enum, value_delimiter = ',', default_values_t = [ChartMethod::Path, ChartMethod::PathLecture, ChartMethod::Whitted])]
    pub methods: Vec<ChartMethod>,
    /// Render time per method, in seconds.
    #[arg(long, default_value_t = 10.0)]
    pub seconds: f64,
    /// Stop a method at this many samples per pixel even before `--seconds`.
    #[arg(long, default_value_t = 65536, value_parser = clap::value_parser!(u32).range(1..))]
    pub max_spp: u32,
    /// Path length limit (Mitsuba's counting for `path`, bounces for `whitted`).
    #[arg(long, default_value_t = 8)]
    pub max_depth: u32,
    /// Seed of the random samples.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Where to write: OUTPUT.csv and OUTPUT.png (replaced if they exist).
    /// Without it: chart.csv and chart.png, or chart-2.csv and
    /// chart-2.png, … — the first pair not yet taken.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// A rendering method `raylab chart` can compare.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ChartMethod {
    /// Path tracing, robust intersections.
    Path,
    /// Path tracing with Owen-scrambled Sobol samples.
    PathSobol,
    /// Path tracing with adaptive sampling (threshold 2%).
    PathAdaptive,
    /// Path tracing with the lecture's sphere and triangle formulas.
    PathLecture,
    /// Whitted ray tracing, robust intersections.
    Whitted,
    /// Whitted ray tracing with the lecture's formulas.
    WhittedLecture,
}

impl ChartMethod {
    /// The name on the command line, in the CSV and in the legend.
    pub fn name(self) -> &'static str {
        match self {
            ChartMethod::Path => "path",
            ChartMethod::PathSobol => "path-sobol",
            ChartMethod::PathAdaptive => "path-adaptive",
            ChartMethod::PathLecture => "path-lecture",
            ChartMethod::Whitted => "whitted",
            ChartMethod::WhittedLecture => "whitted-lecture",
        }
    }
}

/// Arguments of `raylab inspect`.
#[derive(Debug, clap::Args)]
pub struct InspectArgs {
    /// The scene and how to trace it.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The pixel (i, j): column i from the left, row j from the top.
    #[arg(long, num_args = 2, value_names = ["I", "J"], required = true)]
    pub pixel: Vec<u32>,
    /// Re-trace sample K exactly as `raylab render` traces it (pass K of the
    /// film); without it, the ray through the pixel centre P_ij.
    #[arg(long, value_name = "K")]
    pub sample: Option<u32>,
}

/// The scene file and the settings `render` and `inspect` trace it with.
#[derive(Debug, clap::Args)]
pub struct SceneArgs {
    /// The scene file (raylab XML).
    pub scene: PathBuf,
    /// Image width w in pixels (overrides the scene's camera).
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height h in pixels (overrides the scene's camera).
    #[arg(long)]
    pub height: Option<u32>,
    /// Seed of the random sample positions (the same for `render` and `inspect`).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Intersection formulas for spheres and triangles.
    #[arg(long, value_enum, default_value_t = MethodArg::Robust)]
    pub method: MethodArg,
    /// Which integrator estimates each pixel's radiance.
    #[arg(long, value_enum, default_value_t = IntegratorArg::Whitted)]
    pub integrator: IntegratorArg,
    /// whitted: the most reflection/refraction bounces after the first hit;
    /// path: the longest path in segments, counted as Mitsuba counts its
    /// max_depth (1 = emitters seen directly, 2 = direct lighting).
    #[arg(long, default_value_t = 8)]
    pub max_depth: u32,
    /// whitted: a reflection or refraction whose weight in the pixel (the
    /// product of the reflectances and transmittances on its way, largest
    /// channel) is below this is not traced (adaptive tree depth, as
    /// POV-Ray's adc_bailout); 0 traces every bounce to --max-depth.
    #[arg(long, value_name = "WEIGHT", default_value_t = renderer::integrator::MIN_WEIGHT)]
    pub min_weight: f32,
    /// How each pixel's samples draw their random numbers.
    #[arg(long, value_enum, default_value_t = SamplerArg::Independent)]
    pub sampler: SamplerArg,
    /// Adaptive sampling: after 16 passes, pixels whose relative error
    /// (standard error over mean luminance) is below ERROR, with their
    /// neighbours', stop receiving samples; `--adaptive` alone means 0.02.
    #[arg(long, value_name = "ERROR", num_args = 0..=1, default_missing_value = "0.02")]
    pub adaptive: Option<f32>,
}

/// `--sampler`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SamplerArg {
    /// Independent uniform random numbers.
    Independent,
    /// Owen-scrambled Sobol points: each pixel's samples stratified.
    Sobol,
}

impl From<SamplerArg> for renderer::Sampling {
    fn from(arg: SamplerArg) -> Self {
        match arg {
            SamplerArg::Independent => renderer::Sampling::Independent,
            SamplerArg::Sobol => renderer::Sampling::Sobol,
        }
    }
}

/// Arguments of `raylab bench`.
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// What to measure: `suite` (the default: the torus knot, the sphere
    /// field, the seed scene and the scaling table), `interactive`,
    /// `debug-view`, or a scene to measure ray throughput on: a scene or
    /// model file, `knot[:TRIANGLES]`, `spheres[:COUNT]` or `seed`.
    #[arg(default_value = "suite")]
    pub which: String,
    /// The scene of `interactive` and `debug-view` (a file or a generated
    /// scene as above; default: the seed scene).
    #[arg(long)]
    pub scene: Option<String>,
    /// Image width (default: 1280 for the window benchmarks, the scene's own otherwise).
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height (default: 720 for the window benchmarks, the scene's own otherwise).
    #[arg(long)]
    pub height: Option<u32>,
    /// Print the figures as JSON instead of a table.
    #[arg(long)]
    pub json: bool,
    /// interactive: which integrator the window traces with.
    #[arg(long, value_enum, default_value_t = IntegratorArg::Whitted)]
    pub integrator: IntegratorArg,
    /// How many edits to time (interactive: θ, orbit, colour and move in turn).
    #[arg(long, default_value_t = 30, value_parser = clap::value_parser!(u32).range(1..=10000))]
    pub edits: u32,
    /// How many display frames to time (debug-view).
    #[arg(long, default_value_t = 300, value_parser = clap::value_parser!(u32).range(1..=100000))]
    pub frames: u32,
    /// debug-view: keep the debug view hidden, to compare the same frames without it.
    #[arg(long)]
    pub hide_debug_view: bool,
    /// debug-view: let the tracer finish one pass and idle before the frames
    /// are timed, to compare them with the tracer running on every core.
    #[arg(long)]
    pub idle_tracer: bool,
    /// With a scene to measure: first write its triangles (world space; a
    /// plane as a large square of 2 triangles) and the primary and incoherent
    /// rays to this folder as raw little-endian arrays with a manifest.json,
    /// then measure and add raylab's figures to the manifest, so that another
    /// ray tracer can cast the same rays (scripts/bench-vs-embree.sh).
    #[arg(long, value_name = "DIR")]
    pub export: Option<PathBuf>,
}

/// Arguments of `raylab render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// The scene and how to trace it.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Output image: .png (8-bit sRGB) or .exr (linear float32); an
    /// existing file is replaced (and the report says so).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Samples per pixel (progressive passes).
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u32).range(1..=65536))]
    pub spp: u32,
    /// What to write: the final colour, one of the per-pixel AOVs, or a
    /// diagnostic of the passes (variance, cost).
    #[arg(long, value_enum, default_value_t = AovArg::Color)]
    pub aov: AovArg,
    /// A linear EXR of the same scene and size: print the render's relative
    /// MSE, RMSE and mean FLIP (of both clamped and sRGB-encoded, whatever
    /// the view) against it (colour only).
    #[arg(long, value_name = "REF.exr")]
    pub reference: Option<PathBuf>,
    /// Exposure in stops of a PNG: its radiance × 2^EV before the tone
    /// curve (an EXR stays linear). Overrides the scene's <view exposure>.
    #[arg(long, value_name = "EV", allow_hyphen_values = true)]
    pub exposure: Option<f32>,
    /// The tone curve of a PNG. Overrides the scene's <view tonemap>.
    #[arg(long, value_enum)]
    pub tonemap: Option<TonemapArg>,
    /// Render only this rectangle of pixels, for a render split across
    /// processes or machines: columns X0..X1 and rows Y0..Y1, counted from the
    /// top left, X1 and Y1 excluded. The image keeps its full size, the
    /// pixels outside are zero (black), and an EXR records the rectangle for
    /// `raylab merge`. Each pixel is bit for bit the whole render's.
    #[arg(long, num_args = 4, value_names = ["X0", "Y0", "X1", "Y1"])]
    pub crop: Option<Vec<u32>>,
    /// Render only sample indices FROM..TO (TO excluded) of every pixel
    /// instead of `--spp` samples from 0: parts with different ranges are
    /// averaged by `raylab merge`, weighted by their sample counts.
    #[arg(long, value_name = "FROM..TO", value_parser = parse_sample_range, conflicts_with = "spp")]
    pub samples: Option<std::ops::Range<u32>>,
}

/// `--tonemap`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TonemapArg {
    /// Each channel clamped to [0, 1]: exact up to white, highlights clip.
    Clamp,
    /// Khronos PBR Neutral: colours less a small offset up to 0.76, highlights rolled off toward white.
    Neutral,
}

impl From<TonemapArg> for scene::Tonemap {
    fn from(t: TonemapArg) -> Self {
        match t {
            TonemapArg::Clamp => scene::Tonemap::Clamp,
            TonemapArg::Neutral => scene::Tonemap::Neutral,
        }
    }
}

/// `--method`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// The lecture's formulas exactly.
    Lecture,
    /// Numerically robust formulas (default).
    Robust,
}

impl From<MethodArg> for renderer::Method {
    fn from(arg: MethodArg) -> Self {
        match arg {
            MethodArg::Lecture => renderer::Method::Lecture,
            MethodArg::Robust => renderer::Method::Robust,
        }
    }
}

/// `--integrator`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum IntegratorArg {
    /// Whitted's recursive ray tracer (default).
    Whitted,
    /// Path tracing with next-event estimation and MIS (physically based).
    Path,
}

impl From<IntegratorArg> for renderer::integrator::Integrator {
    fn from(arg: IntegratorArg) -> Self {
        match arg {
            IntegratorArg::Whitted => Self::Whitted,
            IntegratorArg::Path => Self::Path,
        }
    }
}

/// `--aov`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum AovArg {
    /// The rendered image.
    Color,
    /// α to the first hit along the unit ray v_ij (EXR channel Z; +∞ on a miss).
    Depth,
    /// Geometric normal at the first hit.
    Normal,
    /// Material albedo at the first hit.
    Albedo,
    /// Index of the object hit (−1 on a miss).
    Object,
    /// Relative variance of each pixel's mean after `--spp` passes, Var[mean] / mean²
    /// (EXR channel `variance`; PNG: a log-scale heatmap).
    Variance,
    /// Shape tests per sample after `--spp` passes (EXR channel `cost`; PNG: a heatmap).
    Cost,
    /// Samples each pixel received: `--adaptive` gives converged pixels fewer (EXR channel `spp`;
    /// PNG: a heatmap).
    Spp,
}

/// `FROM..TO` (sample indices, TO excluded, FROM < TO ≤ 65536).
fn parse_sample_range(text: &str) -> Result<std::ops::Range<u32>, String> {
    let (from, to) = text
        .split_once("..")
        .ok_or_else(|| format!("{text:?}: expected FROM..TO, e.g. 0..64"))?;
    let number = |t: &str| {
        t.trim()
            .parse::<u32>()
            .map_err(|_| format!("{text:?}: {t:?} is not a sample index"))
    };
    let (from, to) = (number(from)?, number(to)?);
    if from >= to || to > 65536 {
        return Err(format!(
            "{text:?}: the range must hold at least one sample, and end by 65536"
        ));
    }
    Ok(from..to)
}
