//! The chart of cycles per frame along the fly-through: one panel per resolution, one line per
//! run at that resolution, and the 60 and 30 fps budgets. Drawn with plotters into memory and
//! encoded as PNG, with the DejaVu font compiled in, so the same figures give the same bytes on
//! every machine.

use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

use portalcast_xtask::bench_log::Run;
use portalcast_xtask::{TaskError, TaskResult};

use super::{CYCLES_PER_FRAME, FONT};

/// Width of the picture, in pixels.
const WIDTH: u32 = 1000;
/// Height of one panel, in pixels.
const PANEL_HEIGHT: u32 = 360;

/// Line colours, in run order (the Tableau 10 palette).
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// One panel: its title and its runs with their legend labels.
pub struct Panel<'r> {
    /// The panel's caption.
    pub title: String,
    /// The runs, each with its legend label.
    pub runs: Vec<(String, &'r Run)>,
    /// The index in `runs` of the run drawn on top, thicker (the bench map's defaults).
    pub highlighted: Option<usize>,
}

/// The colour of the highlighted run.
const HIGHLIGHT: RGBColor = RGBColor(0, 0, 0);

fn chart_error(error: impl std::fmt::Debug) -> TaskError {
    TaskError(format!("drawing the chart: {error:?}"))
}

/// The PNG bytes of the chart of `panels`.
pub fn draw(panels: &[Panel]) -> TaskResult<Vec<u8>> {
    // Registering twice replaces the font with itself.
    register_font(FONT, FontStyle::Normal, dejavu::sans::regular())
        .map_err(|_| TaskError("the DejaVu Sans font does not load".to_string()))?;
    let height = PANEL_HEIGHT * panels.len().max(1) as u32;
    let mut pixels = vec![0u8; (WIDTH * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (WIDTH, height)).into_drawing_area();
        root.fill(&WHITE).map_err(chart_error)?;
        let areas = root.split_evenly((panels.len().max(1), 1));
        for (area, panel) in areas.iter().zip(panels) {
            draw_panel(area, panel)?;
        }
        root.present().map_err(chart_error)?;
    }
    let mut png = Vec::new();
    // Best compression: the chart is committed, and regenerated with every report.
    image::codecs::png::PngEncoder::new_with_quality(
        &mut png,
        image::codecs::png::CompressionType::Best,
        image::codecs::png::FilterType::Adaptive,
    )
    .write_image(&pixels, WIDTH, height, image::ExtendedColorType::Rgb8)
    .map_err(|error| TaskError(format!("encoding the chart: {error}")))?;
    Ok(png)
}

use image::ImageEncoder;

fn draw_panel(
    area: &DrawingArea<BitMapBackend, plotters::coord::Shift>,
    panel: &Panel,
) -> TaskResult<()> {
    let frames = panel
        .runs
        .iter()
        .flat_map(|(_, run)| run.frames.iter().map(|frame| frame.index + 1))
        .max()
        .unwrap_or(1);
    let budgets = [(60, CYCLES_PER_FRAME), (30, 2 * CYCLES_PER_FRAME)];
    let highest = panel
        .runs
        .iter()
        .flat_map(|(_, run)| run.frames.iter().map(|frame| frame.cycles))
        .chain(budgets.iter().map(|(_, cycles)| *cycles))
        .max()
        .unwrap_or(1);
    let top = highest as f64 / 1e6 * 1.08;
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, (FONT, 18))
        .margin(10)
        .x_label_area_size(36)
        .y_label_area_size(64)
        .build_cartesian_2d(0u32..frames.saturating_sub(1).max(1), 0f64..top)
        .map_err(chart_error)?;
    chart
        .configure_mesh()
        .x_desc("frame of the fly-through")
        .y_desc("million cycles")
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 14))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(chart_error)?;
    for (fps, cycles) in budgets {
        let level = cycles as f64 / 1e6;
        chart
            .draw_series(DashedLineSeries::new(
                [(0, level), (frames.saturating_sub(1).max(1), level)],
                6,
                4,
                BLACK.mix(0.5).stroke_width(1),
            ))
            .map_err(chart_error)?
            .label(format!("{fps} fps budget"))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.mix(0.5)));
    }
    // The highlighted run last, so the others do not hide it; the legend follows drawing order.
    let order = (0..panel.runs.len())
        .filter(|index| Some(*index) != panel.highlighted)
        .chain(panel.highlighted);
    for (position, index) in order.enumerate() {
        let (label, run) = &panel.runs[index];
        let (colour, width) = if Some(index) == panel.highlighted {
            (HIGHLIGHT, 3)
        } else {
            (PALETTE[position % PALETTE.len()], 2)
        };
        chart
            .draw_series(LineSeries::new(
                run.frames
                    .iter()
                    .map(|frame| (frame.index, frame.cycles as f64 / 1e6)),
                colour.stroke_width(width),
            ))
            .map_err(chart_error)?
            .label(label.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(width))
            });
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .label_font((FONT, 13))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .draw()
        .map_err(chart_error)?;
    Ok(())
}
