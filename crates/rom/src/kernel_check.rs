//! The kernel check: a deterministic scatter of columns and spans over every kernel variant
//! (texture heights, flat sizes, lit and unlit, both packings). The ROM draws it through the asm
//! kernels and the host through the twins; the emulator test requires identical pages.

use portalcast::raster::column::{ColumnTexture, COLUMN_LOG2_HEIGHTS};
use portalcast::raster::flat::{FlatTexture, PackedUv, FLAT_LOG2_SIDES};
use portalcast::raster::Canvas;

const TEXEL_POOL_SIZE: usize = 4096;

const fn texel_pool() -> [u8; TEXEL_POOL_SIZE] {
    let mut pool = [0u8; TEXEL_POOL_SIZE];
    let mut i = 0;
    while i < TEXEL_POOL_SIZE {
        // Every byte value appears, in an order unlike the index, so a wrong address shows.
        pool[i] = ((i * 37 + (i >> 8) * 11) & 0xff) as u8;
        i += 1;
    }
    pool
}

const fn check_colormap() -> [u8; 256] {
    let mut colormap = [0u8; 256];
    let mut i = 0;
    while i < 256 {
        colormap[i] = ((i * 7 + 3) & 0xff) as u8;
        i += 1;
    }
    colormap
}

static TEXEL_POOL: [u8; TEXEL_POOL_SIZE] = texel_pool();

/// The runs `(top, length)` of the check's sprite columns: a single run, runs with gaps of one
/// and many rows, a one-row run, a run of the whole height and an empty column.
const SPRITE_RUNS: [&[(u8, u8)]; 5] = [
    &[(0, 40)],
    &[(2, 9), (12, 1), (20, 30), (51, 13)],
    &[(63, 1)],
    &[(0, 64)],
    &[],
];

/// Bytes of the check's sprite columns in the post layout (`raster::sprite`).
const SPRITE_POSTS_LEN: usize = {
    let mut len = 0;
    let mut column = 0;
    while column < SPRITE_RUNS.len() {
        len += 1;
        let mut post = 0;
        while post < SPRITE_RUNS[column].len() {
            len += 3 + SPRITE_RUNS[column][post].1 as usize;
            post += 1;
        }
        column += 1;
    }
    len
};

/// The check's sprite columns, one after the other, and where each starts.
const fn sprite_posts() -> ([u8; SPRITE_POSTS_LEN], [usize; SPRITE_RUNS.len()]) {
    let mut posts = [0u8; SPRITE_POSTS_LEN];
    let mut starts = [0usize; SPRITE_RUNS.len()];
    let mut at = 0;
    let mut column = 0;
    while column < SPRITE_RUNS.len() {
        starts[column] = at;
        posts[at] = SPRITE_RUNS[column].len() as u8;
        at += 1;
        let mut post = 0;
        while post < SPRITE_RUNS[column].len() {
            let (top, len) = SPRITE_RUNS[column][post];
            posts[at] = top;
            posts[at + 1] = len;
            at += 2;
            let mut row = 0;
            while row <= len as usize {
                // The pad repeats the last texel.
                let texel_row = if row == len as usize { row - 1 } else { row };
                posts[at] = ((texel_row * 29 + top as usize * 7 + column * 53) & 0xff) as u8;
                at += 1;
                row += 1;
            }
            post += 1;
        }
        column += 1;
    }
    (posts, starts)
}

static SPRITE_POSTS: ([u8; SPRITE_POSTS_LEN], [usize; SPRITE_RUNS.len()]) = sprite_posts();

/// Columns of the check's sprite image ([`SPRITE_IMAGE`]): the five of [`SPRITE_POSTS`], one
/// whose offset lies past the image's end, and one whose second post runs past it; a batch
/// also names a column beyond these, whose offset entry is missing.
const IMAGE_COLUMNS: usize = SPRITE_RUNS.len() + 2;

/// The truncated last column: two posts, the second cut after its first texel.
const TRUNCATED_COLUMN: [u8; 10] = [2, 0, 3, 11, 12, 13, 13, 10, 5, 14];

/// Bytes of [`SPRITE_IMAGE`].
const SPRITE_IMAGE_LEN: usize = 4 * IMAGE_COLUMNS + SPRITE_POSTS_LEN + TRUNCATED_COLUMN.len();

/// The check's sprite image in the layout of `Sprite::posts`: the columns' offsets, then their
/// posts (the batch kernel's input, with every way a column can be cut short).
static SPRITE_IMAGE: [u8; SPRITE_IMAGE_LEN] = {
    let (posts, starts) = sprite_posts();
    let mut image = [0u8; SPRITE_IMAGE_LEN];
    let mut offsets = [0u32; IMAGE_COLUMNS];
    let mut column = 0;
    while column < SPRITE_RUNS.len() {
        offsets[column] = (4 * IMAGE_COLUMNS + starts[column]) as u32;
        column += 1;
    }
    offsets[SPRITE_RUNS.len()] = SPRITE_IMAGE_LEN as u32;
    offsets[SPRITE_RUNS.len() + 1] = (4 * IMAGE_COLUMNS + SPRITE_POSTS_LEN) as u32;
    let mut at = 0;
    while at < IMAGE_COLUMNS {
        let bytes = offsets[at].to_le_bytes();
        let mut byte = 0;
        while byte < 4 {
            image[4 * at + byte] = bytes[byte];
            byte += 1;
        }
        at += 1;
    }
    let mut at = 0;
    while at < SPRITE_POSTS_LEN {
        image[4 * IMAGE_COLUMNS + at] = posts[at];
        at += 1;
    }
    let mut at = 0;
    while at < TRUNCATED_COLUMN.len() {
        image[4 * IMAGE_COLUMNS + SPRITE_POSTS_LEN + at] = TRUNCATED_COLUMN[at];
        at += 1;
    }
    image
};

/// The light rows of the check's batches: every entry a function of its row and index.
static CHECK_LIGHT_ROWS: portalcast_format::Colormap = mixed_table(13, 7, 3);

/// A table whose entry `[row][index]` is `row·row_factor + index·index_factor + offset`, modulo
/// 256: a wrong row or a wrong index shows in what is read from it.
const fn mixed_table<const ROWS: usize>(
    row_factor: usize,
    index_factor: usize,
    offset: usize,
) -> [[u8; 256]; ROWS] {
    let mut table = [[0u8; 256]; ROWS];
    let mut row = 0;
    while row < ROWS {
        let mut index = 0;
        while index < 256 {
            table[row][index] = ((row * row_factor + index * index_factor + offset) & 0xff) as u8;
            index += 1;
        }
        row += 1;
    }
    table
}

/// Sprite batches drawn per call, each of up to [`BATCH_COLUMNS_MAX`] columns.
const BATCHES: u32 = JOBS_PER_KIND / 4;

/// The most columns a check batch has.
const BATCH_COLUMNS_MAX: usize = 8;

/// Portal middles set up per call, each over up to [`MIDDLE_COLUMNS_MAX`] columns.
const MIDDLES: u32 = JOBS_PER_KIND / 8;

/// The most columns a check middle has.
const MIDDLE_COLUMNS_MAX: usize = 16;

/// The check middles' image width: the sprite image's columns rounded up to a power of two
/// (the routine masks the column; the last is past the image's offsets, and skipped).
const MIDDLE_IMAGE_WIDTH: u16 = IMAGE_COLUMNS.next_power_of_two() as u16;

/// The openings the check middles are seen through, by column: windows of every height inside
/// the 80 rows every resolution has, and some empty.
static MIDDLE_OPENINGS: [portalcast::raster::Window; 240] = {
    let mut windows = [portalcast::raster::Window { top: 0, bottom: 0 }; 240];
    let mut x = 0;
    while x < 240 {
        let top = ((x * 37 + 11) % 80) as i16;
        let bottom = if x % 9 == 4 {
            top
        } else {
            top + 1 + ((x * 53 + 7) % (80 - top as usize)) as i16
        };
        windows[x] = portalcast::raster::Window { top, bottom };
        x += 1;
    }
    windows
};

/// A blend table for the check: every entry a function of both indices, so a wrong pixel
/// behind or a wrong texel shows.
static CHECK_BLEND: portalcast_format::BlendTable = mixed_table(3, 5, 7);

static COLORMAP: [u8; 256] = check_colormap();

/// A small deterministic generator (Numerical Recipes' LCG), so both sides draw the same jobs.
struct Lcg(u32);

impl Lcg {
    fn next(&mut self) -> u32 {
        self.0 = self.0.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        self.0
    }

    fn below(&mut self, bound: u32) -> u32 {
        (self.next() >> 8) % bound
    }
}

/// Columns and spans drawn per call.
pub const JOBS_PER_KIND: u32 = 160;

/// Whether column job `job` is drawn unlit: one run of six jobs (one per texture height) in
/// three.
fn unlit_column(job: u32) -> bool {
    (job / 6).is_multiple_of(3)
}

/// Whether flat job `job` is drawn unlit: one run of four jobs (one per flat size) in three, so
/// that the unlit runs, by the halving's runs of four, alternate halved and full.
fn unlit_flat(job: u32) -> bool {
    (job / 4) % 3 == 1
}

/// Draws the kernel check for `seed` on `canvas`.
pub fn draw(canvas: &mut impl Canvas, seed: u32) {
    let mut rng = Lcg(seed);
    let width = canvas.resolution().width() as u32;
    let height = canvas.resolution().height() as u32;
    let heights = *COLUMN_LOG2_HEIGHTS.start()..=*COLUMN_LOG2_HEIGHTS.end();
    let sides = *FLAT_LOG2_SIDES.start()..=*FLAT_LOG2_SIDES.end();
    for job in 0..JOBS_PER_KIND {
        let log2_height = heights.start() + job % (heights.end() - heights.start() + 1);
        let column_start = rng.below((TEXEL_POOL_SIZE >> log2_height) as u32) as usize;
        let texels = &TEXEL_POOL[column_start << log2_height..(column_start + 1) << log2_height];
        let row = rng.below(height);
        let count = 1 + rng.below(height - row);
        let column = ColumnTexture {
            texels,
            log2_height,
            v: rng.next(),
            // Steps from a fraction of a texel to many texels per row, both directions.
            dv: rng.next() >> rng.below(12),
            // One run of six jobs (one per height) in three unlit.
            colormap: if unlit_column(job) {
                None
            } else {
                Some(&COLORMAP)
            },
        };
        // The unlit kernels draw only while their bank is in, else the lit ones draw with an
        // identity row: half the unlit runs each way.
        canvas.prefer_lighting(!(unlit_column(job) && (job / 18).is_multiple_of(2)));
        canvas.column(
            rng.below(width) as usize,
            row as usize,
            count as usize,
            &column,
        );
    }
    // Pairs of neighbouring columns (one kernel at 240 wide): each column's rows drawn at
    // random, so one starts or ends above the other, they share no row, or they match; one
    // in four at two heights (two kernels), one in three with a column unlit.
    for job in 0..JOBS_PER_KIND / 2 {
        let log2_height = heights.start() + job % (heights.end() - heights.start() + 1);
        let x = 2 * rng.below(width / 2) as usize;
        let mut side = |log2_height: u32, lit: bool| {
            let column_start = rng.below((TEXEL_POOL_SIZE >> log2_height) as u32) as usize;
            let row = rng.below(height);
            let count = 1 + rng.below(height - row);
            let texture = ColumnTexture {
                texels: &TEXEL_POOL[column_start << log2_height..(column_start + 1) << log2_height],
                log2_height,
                v: rng.next(),
                dv: rng.next() >> rng.below(12),
                colormap: lit.then_some(&COLORMAP),
            };
            (row as usize, count as usize, texture)
        };
        let second_height = if job % 4 == 3 {
            heights.start() + (log2_height + 1 - heights.start()) % 6
        } else {
            log2_height
        };
        let first = side(log2_height, job % 3 != 1);
        let second = side(second_height, job % 3 != 2);
        canvas.prefer_lighting(job % 2 == 0);
        canvas.column_pair(
            x,
            (first.0, first.1, &first.2),
            (second.0, second.1, &second.2),
        );
    }
    for job in 0..JOBS_PER_KIND {
        let log2_side = sides.start() + job % (sides.end() - sides.start() + 1);
        let texels = &TEXEL_POOL[..1 << (2 * log2_side)];
        let x = rng.below(width);
        let count = 1 + rng.below(width - x);
        let step = |rng: &mut Lcg| (rng.next() as i32) >> (12 + rng.below(8));
        let flat = FlatTexture {
            texels,
            log2_side,
            pos: PackedUv(rng.next()),
            step: PackedUv::pack(step(&mut rng), step(&mut rng), log2_side),
            // One run of four jobs (one per side) in three unlit.
            colormap: if unlit_flat(job) {
                None
            } else {
                Some(&COLORMAP)
            },
        };
        // Half the spans halved (every flat size, lit and unlit): at 240 wide they take the
        // doubled kernels with a doubled step, and odd ends step back.
        canvas.set_halved_flats((job / 4) % 2 == 1);
        canvas.prefer_lighting(!(unlit_flat(job) && (job / 24).is_multiple_of(2)));
        canvas.flat(
            rng.below(height) as usize,
            x as usize,
            count as usize,
            &flat,
        );
    }
    canvas.set_halved_flats(false);
    for job in 0..JOBS_PER_KIND {
        let column = job as usize % SPRITE_RUNS.len();
        let (posts, starts) = &SPRITE_POSTS;
        // From a quarter of a row to eight rows a texel; the texel step the inverse, rounded
        // down, as the things stage's never exceeds it by more than its rounding.
        let scale = (1 << 14) + rng.below(8 << 16) as i32;
        let top = rng.below(height) as i16;
        let bottom = top + 1 + rng.below(height - top as u32) as i16;
        let sprite = portalcast::raster::sprite::SpriteColumn {
            posts: &posts[starts[column]..],
            y_top: ((rng.next() % (2 * height)) as i32 - height as i32) << 16
                | rng.below(1 << 16) as i32,
            scale,
            iscale: ((1u64 << 32) / scale as u64) as u32,
            clip: portalcast::raster::Window { top, bottom },
            colormap: if job % 3 == 0 {
                &portalcast::raster::IDENTITY_ROW
            } else {
                &COLORMAP
            },
            // One job in four translucent, over whatever the earlier jobs drew.
            blend: (job % 4 == 1).then_some(&CHECK_BLEND),
        };
        canvas.sprite_column(rng.below(width) as usize, &sprite);
    }
    let mut records = [portalcast::raster::sprite::BatchColumn::default(); BATCH_COLUMNS_MAX];
    for batch in 0..BATCHES {
        let count = 1 + rng.below(BATCH_COLUMNS_MAX as u32) as usize;
        for record in &mut records[..count] {
            let scale = (1 << 14) + rng.below(8 << 16) as i32;
            let top = rng.below(height) as i16;
            let bottom = top + 1 + rng.below(height - top as u32) as i16;
            *record = portalcast::raster::sprite::BatchColumn {
                x: rng.below(width) as u8,
                // One column past the image's: its offset entry is missing.
                column: rng.below(IMAGE_COLUMNS as u32 + 1) as u8,
                // Unlit, each light row, and one past them (skipped).
                light_row: match rng.below(portalcast_format::LIGHT_LEVELS as u32 + 2) {
                    0 => u8::MAX,
                    row => (row - 1) as u8,
                },
                clip: portalcast::raster::Window { top, bottom },
                y_top: ((rng.next() % (2 * height)) as i32 - height as i32) << 16
                    | rng.below(1 << 16) as i32,
                scale,
                iscale: ((1u64 << 32) / scale as u64) as u32,
            };
        }
        canvas.sprite_columns(&portalcast::raster::sprite::SpriteBatch {
            posts: &SPRITE_IMAGE,
            columns: &records[..count],
            colormap: &CHECK_LIGHT_ROWS,
            // One batch in three translucent.
            blend: (batch % 3 == 2).then_some(&CHECK_BLEND),
        });
    }
    draw_middles(canvas, &mut rng);
}

/// Portal middles on random walls in eye space: each one's columns from the canvas's routine
/// (the GBA's `asm/middle.s`) or its twin, drawn by the batch kernel, so the pages differ where
/// the two disagree on a column that shows. The walls lie in front of the eye or cross its
/// plane, face it or not, from a unit to thousands away (the nearest clamp, rays past either
/// end, steep and grazing angles), under every lighting rule.
fn draw_middles(canvas: &mut impl Canvas, rng: &mut Lcg) {
    use portalcast::math::{Angle, EyePoint, Fx24_8, WorldPoint};
    use portalcast::render::light::Lighting;
    use portalcast::render::things::{middle_columns_of, MiddleSetup};
    use portalcast::render::view::{Camera, View};
    let resolution = canvas.resolution();
    let width = resolution.width() as u32;
    let mut out = [portalcast::raster::sprite::BatchColumn::default(); MIDDLE_COLUMNS_MAX];
    for job in 0..MIDDLES {
        let lighting = [Lighting::Off, Lighting::Sector, Lighting::SectorDepth][job as usize % 3];
        let settings = portalcast::render::view::Settings {
            lighting,
            ..crate::bench::default_settings(resolution)
        };
        let camera = Camera {
            position: WorldPoint::default(),
            eye_z: Fx24_8::from_int(32),
            angle: Angle::from_bits(0),
            sector: 0,
            look_lines: rng.below(81) as i32 - 40,
        };
        let view = View::new(&camera, &settings);
        // Up to 4,096 units across, from one unit deep (a sixteenth of the time 1/256 of one).
        let point = |rng: &mut Lcg| {
            let depth_bits = if rng.below(16) == 0 { 1 } else { 256 };
            EyePoint {
                x: Fx24_8::from_bits(rng.below(1 << 21) as i32 - (1 << 20)),
                z: Fx24_8::from_bits(depth_bits + rng.below(1 << 20) as i32 - (1 << 18)),
            }
        };
        let ends = (point(rng), point(rng));
        let first = rng.below(width) as i32;
        let end =
            first + 1 + rng.below((width - first as u32).min(MIDDLE_COLUMNS_MAX as u32)) as i32;
        let light = rng.below(256) as u8;
        let setup = MiddleSetup::new(
            &view,
            ends,
            first,
            rng.below(256) as i32 - 64,
            (rng.below(1 << 20) as i32, rng.below(256) as i16 - 128),
            MIDDLE_IMAGE_WIDTH,
            light,
        );
        let written = middle_columns_of(
            canvas,
            &setup,
            first..end,
            &MIDDLE_OPENINGS,
            &mut out,
            (light, lighting),
        );
        canvas.sprite_columns(&portalcast::raster::sprite::SpriteBatch {
            posts: &SPRITE_IMAGE,
            columns: &out[..written],
            colormap: &CHECK_LIGHT_ROWS,
            blend: None,
        });
    }
}
