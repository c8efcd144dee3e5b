//! Figures: series of points with a style, labelled axes; rendered by [`super::plot`].

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Style {
    Line,
    Dashed,
    Markers,
    Crosses,
}

#[derive(Debug, Clone)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
    /// Palette index; None: the series' position.
    pub color: Option<usize>,
    /// Vertical error bars (x, low, high).
    pub bars: Vec<(f64, f64, f64)>,
    /// Stroke width in pixels: 2, or 1 for a thin series ([`Series::thin`]).
    pub width: u32,
}

impl Series {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, style: Style) -> Self {
        Self {
            label: label.into(),
            points,
            style,
            color: None,
            bars: Vec::new(),
            width: 2,
        }
    }
    pub fn with_bars(mut self, bars: Vec<(f64, f64, f64)>) -> Self {
        self.bars = bars;
        self
    }
    /// Same colour as series `index` of the figure (e.g. both bounds of a band).
    pub fn colored(mut self, index: usize) -> Self {
        self.color = Some(index);
        self
    }
    /// Drawn with a thin stroke: a third way, beside colour and style, to tell series
    /// apart (e.g. a second lambda where the style already tells the rule).
    pub fn thin(mut self) -> Self {
        self.width = 1;
        self
    }
}

#[derive(Debug, Clone)]
pub struct Figure {
    pub name: String,
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    pub log_x: bool,
    pub log_y: bool,
    /// Where the x axis is labelled, when the data sit at a few chosen values (e.g. the
    /// bandwidths of a study); None: evenly by the axis' span.
    pub x_keys: Option<Vec<f64>>,
    /// One unit of x as long as one unit of y on the page (maps: circles stay round);
    /// linear axes only.
    pub equal_axes: bool,
}

impl Figure {
    pub fn new(name: &str, title: &str, x_label: &str, y_label: &str) -> Self {
        Self {
            name: name.into(),
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            log_x: false,
            log_y: false,
            x_keys: None,
            equal_axes: false,
        }
    }
    pub fn with(mut self, s: Series) -> Self {
        self.series.push(s);
        self
    }
    /// Adds the series `label` of `points` drawn as `style` (a series needing bars or a
    /// colour of its own goes through [`Self::with`]).
    pub fn plot(self, label: impl Into<String>, points: Vec<(f64, f64)>, style: Style) -> Self {
        self.with(Series::new(label, points, style))
    }
    pub fn log_log(mut self) -> Self {
        self.log_x = true;
        self.log_y = true;
        self
    }
}
