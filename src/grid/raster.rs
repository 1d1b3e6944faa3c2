//! Flat 2D arrays: the decoded image ([`Raster`]) and any per-cell data ([`Grid`]).

/// A rectangular array of cells stored row-major from the top-left, as images are.
///
/// `x` grows to the right and `y` downwards; cell `(x, y)` is `cells[y * width + x]`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Grid<T> {
    width: usize,
    height: usize,
    cells: Vec<T>,
}

impl<T: Clone> Grid<T> {
    /// A `width` x `height` grid with every cell set to `value`.
    pub fn new(width: usize, height: usize, value: T) -> Self {
        Grid { width, height, cells: vec![value; width * height] }
    }
}

impl<T> Grid<T> {
    /// Wraps row-major `cells`; `None` if their number is not `width * height`.
    pub fn from_vec(width: usize, height: usize, cells: Vec<T>) -> Option<Self> {
        (width.checked_mul(height) == Some(cells.len())).then_some(Grid { width, height, cells })
    }

    /// Number of columns.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Number of rows.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.cells.len()
    }

    /// True when the grid has no cells.
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }

    /// Whether `(x, y)` lies on the grid (signed, so that neighbours of border cells can be asked).
    pub fn contains(&self, x: i64, y: i64) -> bool {
        x >= 0 && y >= 0 && (x as u64) < self.width as u64 && (y as u64) < self.height as u64
    }

    /// The cell at `(x, y)`, or `None` off the grid.
    pub fn get(&self, x: i64, y: i64) -> Option<&T> {
        self.contains(x, y).then(|| &self.cells[y as usize * self.width + x as usize])
    }

    /// The cell at `(x, y)`. Panics off the grid; for hot loops that have checked bounds.
    #[inline]
    pub fn at(&self, x: usize, y: usize) -> &T {
        &self.cells[y * self.width + x]
    }

    /// Mutable access to the cell at `(x, y)`. Panics off the grid.
    #[inline]
    pub fn at_mut(&mut self, x: usize, y: usize) -> &mut T {
        &mut self.cells[y * self.width + x]
    }

    /// Row `y` as a slice. Panics if `y >= height`.
    pub fn row(&self, y: usize) -> &[T] {
        &self.cells[y * self.width..(y + 1) * self.width]
    }

    /// All cells, row-major.
    pub fn cells(&self) -> &[T] {
        &self.cells
    }

    /// All cells, row-major, mutable.
    pub fn cells_mut(&mut self) -> &mut [T] {
        &mut self.cells
    }

    /// Consumes the grid, returning its cells.
    pub fn into_cells(self) -> Vec<T> {
        self.cells
    }

    /// A grid of the same size with `f` applied to every cell.
    pub fn map<U>(&self, f: impl FnMut(&T) -> U) -> Grid<U> {
        Grid { width: self.width, height: self.height, cells: self.cells.iter().map(f).collect() }
    }
}

/// A decoded grayscale image with optional transparency, at 16-bit precision.
///
/// Colour images are reduced to the mean of their red, green and blue samples, as ROS
/// map_server does; 8-bit samples are scaled by 257 so that 255 becomes 65535.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Raster {
    /// Gray level per pixel, 0 = black, 65535 = white.
    pub gray: Grid<u16>,
    /// Opacity per pixel, 0 = transparent, 65535 = opaque; `None` when the image has no alpha.
    pub alpha: Option<Grid<u16>>,
}

impl Raster {
    /// Image width in pixels.
    pub fn width(&self) -> usize {
        self.gray.width()
    }

    /// Image height in pixels.
    pub fn height(&self) -> usize {
        self.gray.height()
    }
}
