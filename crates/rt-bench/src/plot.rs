//! Error-against-time plots as PNG: log–log axes, one curve per setting. plotters
//! draws the geometry into a pixel buffer; its text needs font features that rt does
//! without, so the labels are drawn afterwards with the public-domain 8×8 bitmap font.

use anyhow::{Context, Result, anyhow};
use font8x8::legacy::BASIC_LEGACY;
use image::RgbImage;
use plotters::prelude::*;
use std::path::Path;

pub struct Curve {
    pub label: String,
    /// (seconds, relative RMSE), in order of samples per pixel.
    pub points: Vec<(f64, f64)>,
    /// Drawn thin and marked in the legend: no point of it is on the Pareto front.
    pub dominated: bool,
}

const WIDTH: u32 = 820;
const HEIGHT: u32 = 540;
/// Plot area: left, top, right, bottom edges in pixels.
const AREA: (i32, i32, i32, i32) = (72, 40, 600, 490);
const COLORS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// Writes `path`: each curve's points (time in ms across, relative RMSE in % up), with
/// grey guides at the target error and the time budget.
pub fn error_vs_time(path: &Path, title: &str, curves: &[Curve], target: f64, budget_s: f64) -> Result<()> {
    let all: Vec<(f64, f64)> =
        curves.iter().flat_map(|c| c.points.iter().copied()).filter(|(t, e)| *t > 0.0 && *e > 0.0).collect();
    let span = |v: Vec<f64>| {
        let lo = v.iter().copied().fold(f64::MAX, f64::min);
        let hi = v.iter().copied().fold(f64::MIN, f64::max);
        if lo > hi { (0.1, 10.0) } else { decade_bounds(lo, hi) }
    };
    let mut times: Vec<f64> = all.iter().map(|p| p.0 * 1e3).collect();
    times.push(budget_s * 1e3);
    let mut errors: Vec<f64> = all.iter().map(|p| p.1 * 100.0).collect();
    errors.push(target * 100.0);
    let (x_range, y_range) = (span(times), span(errors));

    let mut buffer = vec![255u8; (WIDTH * HEIGHT * 3) as usize];
    let mut labels: Vec<(String, i32, i32, [u8; 3])> = Vec::new();
    {
        let root = BitMapBackend::with_buffer(&mut buffer, (WIDTH, HEIGHT)).into_drawing_area();
        let area = root.margin(AREA.1 as u32, HEIGHT - AREA.3 as u32, AREA.0 as u32, WIDTH - AREA.2 as u32);
        let mut chart = ChartBuilder::on(&area)
            .build_cartesian_2d((x_range.0..x_range.1).log_scale(), (y_range.0..y_range.1).log_scale())
            .map_err(|e| anyhow!("plot: {e}"))?;
        let grey = RGBColor(225, 225, 225);
        for x in grid(x_range) {
            chart.draw_series(LineSeries::new([(x, y_range.0), (x, y_range.1)], grey)).map_err(|e| anyhow!("{e}"))?;
            if is_decade(x) || x_range.1 / x_range.0 <= 10.0 {
                let (px, _) = chart.backend_coord(&(x, y_range.0));
                let text = number(x);
                labels.push((text.clone(), px - 4 * text.len() as i32, AREA.3 + 6, [0; 3]));
            }
        }
        for y in grid(y_range) {
            chart.draw_series(LineSeries::new([(x_range.0, y), (x_range.1, y)], grey)).map_err(|e| anyhow!("{e}"))?;
            if is_decade(y) || y_range.1 / y_range.0 <= 10.0 {
                let (_, py) = chart.backend_coord(&(x_range.0, y));
                let text = format!("{}%", number(y));
                labels.push((text.clone(), AREA.0 - 6 - 8 * text.len() as i32, py - 4, [0; 3]));
            }
        }
        let guide = RGBColor(150, 150, 150);
        let (target, budget) = (target * 100.0, budget_s * 1e3);
        chart
            .draw_series(DashedLineSeries::new([(x_range.0, target), (x_range.1, target)], 6, 4, guide.into()))
            .map_err(|e| anyhow!("{e}"))?;
        chart
            .draw_series(DashedLineSeries::new([(budget, y_range.0), (budget, y_range.1)], 6, 4, guide.into()))
            .map_err(|e| anyhow!("{e}"))?;
        for (i, curve) in curves.iter().enumerate() {
            let color = COLORS[i % COLORS.len()];
            let points: Vec<(f64, f64)> = curve.points.iter().map(|(t, e)| (t * 1e3, e * 100.0)).collect();
            let line = if curve.dominated { color.stroke_width(1) } else { color.stroke_width(2) };
            chart.draw_series(LineSeries::new(points.clone(), line)).map_err(|e| anyhow!("{e}"))?;
            let marker = if curve.dominated { color.stroke_width(1) } else { color.filled() };
            chart.draw_series(points.iter().map(|p| Circle::new(*p, 3, marker))).map_err(|e| anyhow!("{e}"))?;
            let y = AREA.1 + 6 + 16 * i as i32;
            root.draw(&Rectangle::new([(AREA.2 + 16, y), (AREA.2 + 34, y + 8)], color.filled()))
                .map_err(|e| anyhow!("{e}"))?;
            let suffix = if curve.dominated { " (dominated)" } else { "" };
            labels.push((format!("{}{suffix}", curve.label), AREA.2 + 40, y, [0; 3]));
        }
        root.draw(&Rectangle::new([(AREA.0, AREA.1), (AREA.2, AREA.3)], BLACK)).map_err(|e| anyhow!("{e}"))?;
        root.present().map_err(|e| anyhow!("{e}"))?;
    }
    let mut image = RgbImage::from_raw(WIDTH, HEIGHT, buffer).context("plot buffer size")?;
    labels.push((title.to_string(), AREA.0, 12, [0; 3]));
    labels.push(("time (ms, log)".into(), (AREA.0 + AREA.2) / 2 - 56, AREA.3 + 26, [80; 3]));
    labels.push(("relative RMSE (log); dashed: target and budget".into(), AREA.0, AREA.1 - 14, [80; 3]));
    for (text, x, y, color) in labels {
        draw_text(&mut image, &text, x, y, color);
    }
    rt::render::write_png(&image, path)
}

/// Whole decades around [lo, hi].
fn decade_bounds(lo: f64, hi: f64) -> (f64, f64) {
    let lo = 10f64.powf(lo.log10().floor());
    let hi = 10f64.powf(hi.log10().ceil());
    if hi > lo { (lo, hi) } else { (lo, lo * 10.0) }
}

/// 1, 2 and 5 times each decade inside the range.
fn grid((lo, hi): (f64, f64)) -> Vec<f64> {
    let first = lo.log10().floor() as i32;
    let last = hi.log10().ceil() as i32;
    (first..=last)
        .flat_map(|k| [1.0, 2.0, 5.0].map(|m| m * 10f64.powi(k)))
        .filter(|v| *v >= lo * 0.999 && *v <= hi * 1.001)
        .collect()
}

fn is_decade(v: f64) -> bool {
    (v.log10() - v.log10().round()).abs() < 1e-9
}

/// Short decimal: 0.001, 0.5, 20, 1000, 1e+06.
fn number(v: f64) -> String {
    if !(1e-3..1e5).contains(&v) {
        return format!("{v:.0e}");
    }
    let s = format!("{v:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// ASCII text in the 8×8 font, top-left at (x, y); pixels off the image are skipped.
fn draw_text(image: &mut RgbImage, text: &str, x: i32, y: i32, color: [u8; 3]) {
    for (i, c) in text.chars().enumerate() {
        let glyph = BASIC_LEGACY.get(c as usize).copied().unwrap_or(BASIC_LEGACY[b'?' as usize]);
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..8 {
                let (px, py) = (x + 8 * i as i32 + col, y + row as i32);
                if bits & (1 << col) != 0
                    && px >= 0
                    && py >= 0
                    && (px as u32) < image.width()
                    && (py as u32) < image.height()
                {
                    image.put_pixel(px as u32, py as u32, image::Rgb(color));
                }
            }
        }
    }
}
