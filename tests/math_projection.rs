//! Eye space, the column rule, near clipping and the plane projections, against i128 and f64.

use portalcast::math::{
    clip_to_near_plane, Angle, EyeFrame, EyePoint, Fx16_16, Fx24_8, Fx2_30, Side, Viewport,
    WorldPoint, NEAR_DEPTH,
};
use portalcast_format::limits::{EYE_DEPTH_MAX, HEIGHT_DIFF_MAX, WORLD_COORD_MAX};
use proptest::prelude::*;

/// The four logical screens: 240×160, 240×80, 120×160, 120×80.
const SCREENS: [(i32, i32); 4] = [(240, 160), (240, 80), (120, 160), (120, 80)];

const DEPTH_MAX_BITS: i32 = EYE_DEPTH_MAX << 8;

fn eye_point(x: i32, z: i32) -> EyePoint {
    EyePoint::new(Fx24_8::from_bits(x), Fx24_8::from_bits(z))
}

/// Reference column rule in i128: the smallest `c` with `x0 ≤ c + ½`, `x0 = cx + d·X/Z`,
/// i.e. `c = cx + ceil((2dX − Z) / 2Z)`, clamped to `[0, width]`.
fn reference_first_column(view: &Viewport, p: EyePoint) -> i32 {
    let (x, z) = (p.x.to_bits() as i128, p.z.to_bits() as i128);
    let numerator = 2 * view.focal_x as i128 * x - z;
    let offset = -((-numerator).div_euclid(2 * z)); // ceil
    (view.centre_x() as i128 + offset).clamp(0, view.width as i128) as i32
}

fn in_front() -> impl Strategy<Value = EyePoint> {
    (-DEPTH_MAX_BITS..=DEPTH_MAX_BITS, 1..=DEPTH_MAX_BITS).prop_map(|(x, z)| eye_point(x, z))
}

/// Points that project onto or near the screen (where the column search does real work).
fn near_the_screen() -> impl Strategy<Value = EyePoint> {
    (1..=DEPTH_MAX_BITS, -1100i32..=1100).prop_map(|(z, slope_per_mille)| {
        eye_point((z as i64 * slope_per_mille as i64 / 1000) as i32, z)
    })
}

fn screen() -> impl Strategy<Value = Viewport> {
    (0..4usize).prop_map(|i| Viewport::new(SCREENS[i].0, SCREENS[i].1))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10000))]

    #[test]
    fn first_column_is_the_exact_rule(view in screen(), p in prop_oneof![in_front(), near_the_screen()]) {
        let first = view.first_column_at_or_after(p);
        prop_assert_eq!(first, reference_first_column(&view, p));
        // The defining inequalities, with the continuous position as f64 away from ties.
        if first > 0 && first < view.width {
            prop_assert_ne!(view.side_of_column_ray(p, first), Side::Right);
            prop_assert_eq!(view.side_of_column_ray(p, first - 1), Side::Right);
        }
        let x = view.centre_x() as f64 + view.focal_x as f64 * p.x.to_bits() as f64 / p.z.to_bits() as f64;
        let float_first = (x - 0.5).ceil().clamp(0.0, view.width as f64) as i32;
        if ((x - 0.5) - (x - 0.5).round()).abs() > 1e-6 {
            prop_assert_eq!(first, float_first);
        }
    }

    #[test]
    fn column_ray_side_is_exact_in_front_and_behind(
        view in screen(), column in -10i32..250,
        x in -DEPTH_MAX_BITS..=DEPTH_MAX_BITS, z in -DEPTH_MAX_BITS..=DEPTH_MAX_BITS,
    ) {
        let column = column.min(view.width);
        let p = eye_point(x, z);
        // Sign of cross((2(c − cx) + 1, 2d), (X, Z)) taken as "left of the ray".
        let ray = (2 * (column - view.centre_x()) + 1) as i128 * z as i128;
        let point = 2 * view.focal_x as i128 * x as i128;
        let expected = match point.cmp(&ray) {
            std::cmp::Ordering::Less => Side::Left,
            std::cmp::Ordering::Equal => Side::On,
            std::cmp::Ordering::Greater => Side::Right,
        };
        prop_assert_eq!(view.side_of_column_ray(p, column), expected);
    }

    #[test]
    fn adjacent_walls_claim_every_column_once(
        view in screen(),
        chain in prop::collection::vec((1..=DEPTH_MAX_BITS, -1300i32..=1300), 2..10),
    ) {
        // A chain of walls in front of the eye, left to right: vertex i is shared by walls i−1
        // and i. Each column between the first and last vertex must have exactly one owner
        // under the rule x0 ≤ c + ½ < x1, evaluated as exact rationals.
        let mut vertices: Vec<EyePoint> = chain
            .iter()
            .map(|&(z, slope)| eye_point((z as i64 * slope as i64 / 1000) as i32, z))
            .collect();
        vertices.sort_by(|a, b| {
            (a.x.to_bits() as i128 * b.z.to_bits() as i128).cmp(&(b.x.to_bits() as i128 * a.z.to_bits() as i128))
        });
        let firsts: Vec<i32> = vertices.iter().map(|&v| view.first_column_at_or_after(v)).collect();
        let owns = |wall: usize, column: i32| {
            // x0 ≤ c + ½  ⟺  2dX0 ≤ (2(c − cx) + 1)·Z0, and c + ½ < x1 likewise strict.
            let k = (2 * (column - view.centre_x()) + 1) as i128;
            let (a, b) = (vertices[wall], vertices[wall + 1]);
            2 * view.focal_x as i128 * a.x.to_bits() as i128 <= k * a.z.to_bits() as i128
                && k * (b.z.to_bits() as i128) < 2 * view.focal_x as i128 * b.x.to_bits() as i128
        };
        for column in 0..view.width {
            let owners: Vec<usize> = (0..vertices.len() - 1).filter(|&wall| owns(wall, column)).collect();
            let by_ranges: Vec<usize> = (0..vertices.len() - 1)
                .filter(|&wall| firsts[wall] <= column && column < firsts[wall + 1])
                .collect();
            prop_assert_eq!(&owners, &by_ranges, "column {}", column);
            let covered = column >= firsts[0] && column < firsts[vertices.len() - 1];
            prop_assert_eq!(owners.len(), covered as usize, "column {} owners {:?}", column, owners);
        }
    }

    #[test]
    fn a_sector_around_the_eye_covers_the_screen_exactly_once(
        view in screen(),
        eye in (-2000i32..2000, -2000i32..2000),
        eye_fraction in (0i32..256, 0i32..256),
        view_angle in any::<u16>(),
        radius in 40i32..3000,
        (offset, jitters) in (0u16..3600, (3usize..16).prop_flat_map(|n| prop::collection::vec(0u16..(1200 / n as u16), n))),
    ) {
        // A convex sector (integer vertices near a circle, clockwise with y down) around an eye
        // at a fractional position: walls transformed, clipped to the near plane and projected
        // with the column rule must tile [0, width) with no gap and no overlap.
        let n = jitters.len();
        let mut angles: Vec<u16> = jitters
            .iter()
            .enumerate()
            .map(|(i, &jitter)| (offset + (i * 3600 / n) as u16 + jitter) % 3600)
            .collect();
        angles.sort_unstable();
        angles.dedup();
        let vertices: Vec<WorldPoint> = angles
            .iter()
            .map(|&tenths| {
                let radians = (tenths as f64 / 10.0).to_radians();
                WorldPoint::from_int(
                    eye.0 + (radius as f64 * radians.cos()).round() as i32,
                    eye.1 + (radius as f64 * radians.sin()).round() as i32,
                )
            })
            .collect();
        let n = vertices.len();
        prop_assume!(n >= 3);
        prop_assume!((0..n).all(|i| portalcast::math::cross(vertices[i], vertices[(i + 1) % n], vertices[(i + 2) % n]) > 0));
        let position = WorldPoint::new(
            Fx24_8::from_bits((eye.0 << 8) + eye_fraction.0),
            Fx24_8::from_bits((eye.1 << 8) + eye_fraction.1),
        );
        let frame = EyeFrame::new(position, Angle::from_bits(view_angle));
        let mut owners = vec![0u32; view.width as usize];
        for i in 0..n {
            let (a, b) = (frame.to_eye(vertices[i]), frame.to_eye(vertices[(i + 1) % n]));
            if let Some(visible) = clip_to_near_plane(a, b) {
                let start = view.first_column_at_or_after(visible.start);
                let end = view.first_column_at_or_after(visible.end);
                for column in start..end {
                    owners[column as usize] += 1;
                }
            }
        }
        prop_assert!(owners.iter().all(|&count| count == 1), "owners per column: {:?}", owners);
    }

    #[test]
    fn near_clipping_is_the_exact_intersection(
        a in (-DEPTH_MAX_BITS..=DEPTH_MAX_BITS, -DEPTH_MAX_BITS..=DEPTH_MAX_BITS),
        b in (-DEPTH_MAX_BITS..=DEPTH_MAX_BITS, -1024i32..=DEPTH_MAX_BITS),
    ) {
        let (a, b) = (eye_point(a.0, a.1), eye_point(b.0, b.1));
        let near = NEAR_DEPTH.to_bits();
        let clipped = clip_to_near_plane(a, b);
        let (a_in, b_in) = (a.z.to_bits() >= near, b.z.to_bits() >= near);
        prop_assert_eq!(clipped.is_some(), a_in || b_in);
        if let Some(segment) = clipped {
            prop_assert!(segment.start.z.to_bits() >= near && segment.end.z.to_bits() >= near);
            if a_in { prop_assert_eq!(segment.start, a); prop_assert_eq!(segment.t_start, Fx2_30::ZERO); }
            if b_in { prop_assert_eq!(segment.end, b); prop_assert_eq!(segment.t_end, Fx2_30::ONE); }
            if a_in != b_in {
                let cut = if a_in { segment.end } else { segment.start };
                let t = if a_in { segment.t_end } else { segment.t_start };
                prop_assert_eq!(cut.z, NEAR_DEPTH);
                // x and t against exact rationals: error ≤ ½ ulp each.
                let (ax, az) = (a.x.to_bits() as i128, a.z.to_bits() as i128);
                let (bx, bz) = (b.x.to_bits() as i128, b.z.to_bits() as i128);
                let (num, den) = ((near as i128 - az), (bz - az));
                let x_twice_error = 2 * ((cut.x.to_bits() as i128 - ax) * den - (bx - ax) * num);
                prop_assert!(x_twice_error.abs() <= den.abs(), "x error");
                let t_twice_error = 2 * (t.to_bits() as i128 * den - (num << 30));
                prop_assert!(t_twice_error.abs() <= den.abs(), "t error");
            }
        }
    }

    #[test]
    fn eye_transform_is_within_its_bound(
        p in (-WORLD_COORD_MAX << 8..=WORLD_COORD_MAX << 8, -WORLD_COORD_MAX << 8..=WORLD_COORD_MAX << 8),
        e in (-WORLD_COORD_MAX << 8..=WORLD_COORD_MAX << 8, -WORLD_COORD_MAX << 8..=WORLD_COORD_MAX << 8),
        angle in any::<u16>(),
    ) {
        let point = WorldPoint::new(Fx24_8::from_bits(p.0), Fx24_8::from_bits(p.1));
        let frame = EyeFrame::new(WorldPoint::new(Fx24_8::from_bits(e.0), Fx24_8::from_bits(e.1)), Angle::from_bits(angle));
        let q = frame.to_eye(point);
        let radians = angle as f64 * std::f64::consts::TAU / 65536.0;
        let (dx, dy) = ((p.0 - e.0) as f64 / 256.0, (p.1 - e.1) as f64 / 256.0);
        let x = -dx * radians.sin() + dy * radians.cos();
        let z = dx * radians.cos() + dy * radians.sin();
        // ½ ulp of rounding plus the sine table's 7.93e-6 on each of |dx|, |dy|.
        let bound = 0.5 / 256.0 + (dx.abs() + dy.abs()) * 7.93e-6;
        prop_assert!((q.x.to_bits() as f64 / 256.0 - x).abs() <= bound);
        prop_assert!((q.z.to_bits() as f64 / 256.0 - z).abs() <= bound);
        // And back: to_world(to_eye(p)) is p within twice the rotation error plus the roundings.
        let back = frame.to_world(q);
        let back_bound = 2.0 / 256.0 + 2.0 * (dx.abs() + dy.abs()) * 7.93e-6 * 1.5;
        prop_assert!(((back.x - point.x).to_bits() as f64 / 256.0).abs() <= back_bound);
        prop_assert!(((back.y - point.y).to_bits() as f64 / 256.0).abs() <= back_bound);
    }

    #[test]
    fn continuous_x_within_its_bound(view in screen(), p in prop_oneof![in_front(), near_the_screen()]) {
        prop_assume!(p.z >= NEAR_DEPTH);
        let exact = view.projected_x_exact(p);
        let approx = view.projected_x_saturating(p);
        let magnitude = (exact.to_bits() as f64).abs();
        let relative = 1e-9 + p.z.to_bits() as f64 / 256.0 / (1u64 << 31) as f64;
        prop_assert!(
            (approx.to_bits() as f64 - exact.to_bits() as f64).abs() <= magnitude * relative + 1.0,
            "{:?} vs {:?}", approx, exact
        );
        let real = view.centre_x() as f64 + view.focal_x as f64 * p.x.to_bits() as f64 / p.z.to_bits() as f64;
        let expected = (real * 65536.0).round().clamp(i32::MIN as f64, i32::MAX as f64);
        prop_assert!((exact.to_bits() as f64 - expected).abs() <= 1.0);
    }

    #[test]
    fn floor_depth_of_every_row(
        view in screen(), horizon in 0i32..=160, row in 0i32..160,
        eye_above_plane in -(HEIGHT_DIFF_MAX << 8)..=HEIGHT_DIFF_MAX << 8,
    ) {
        let mut view = view;
        view.horizon_y = horizon.min(view.height);
        let row = row.min(view.height - 1);
        let depth = view.floor_depth_of_row(Fx24_8::from_bits(eye_above_plane), row);
        let offset = 2 * (row - view.horizon_y) + 1;
        let visible = eye_above_plane != 0 && (eye_above_plane > 0) == (offset > 0);
        prop_assert_eq!(depth.is_some(), visible);
        if let Some(depth) = depth {
            // z' = 2·d·Δ / offset: relative error ≤ |offset|·2^-31, plus ½ ulp.
            let exact = 2.0 * view.focal_y as f64 * eye_above_plane as f64 / offset as f64;
            let bound = exact.abs() * offset.abs() as f64 / (1u64 << 31) as f64 + 0.5;
            prop_assert!((depth.to_bits() as f64 - exact).abs() <= bound);
            prop_assert!(depth.to_bits() > 0);
        }
    }

    #[test]
    fn row_of_a_height(
        view in screen(),
        height_above_eye in -(HEIGHT_DIFF_MAX << 8)..=HEIGHT_DIFF_MAX << 8,
        depth in NEAR_DEPTH.to_bits()..=DEPTH_MAX_BITS,
    ) {
        let z = Fx24_8::from_bits(depth);
        let y = view.projected_y(Fx24_8::from_bits(height_above_eye), z.recip_fx2_30());
        let exact = view.horizon_y as f64 * 256.0 - view.focal_y as f64 * height_above_eye as f64 * 256.0 / depth as f64;
        // 1/z' error (1e-9 relative + 2^-31) times d·Δh, plus ½ ulp of the product.
        let scaled = view.focal_y as f64 * height_above_eye.unsigned_abs() as f64;
        let bound = scaled * (1e-9 * 256.0 / depth as f64 + 1.0 / (1u64 << 31) as f64) + 0.5;
        prop_assert!((y.to_bits() as f64 - exact).abs() <= bound, "{} vs {}", y.to_bits(), exact);
        let first = view.first_row_at_or_after(y);
        prop_assert!((0..=view.height).contains(&first));
    }
}

#[test]
fn column_centres_and_one_ulp_either_side() {
    let view = Viewport::new(240, 160);
    // x' = z'·(c + ½ − cx)/d exactly on the centre of column 150: owned by 150 (x0 ≤ c + ½).
    let z = 120 << 8;
    let on_centre = eye_point((150 - 120) * 256 + 128, z); // x = cx + d·x'/z' = 150.5
    assert_eq!(view.side_of_column_ray(on_centre, 150), Side::On);
    assert_eq!(view.first_column_at_or_after(on_centre), 150);
    let just_right = eye_point((150 - 120) * 256 + 129, z);
    assert_eq!(view.first_column_at_or_after(just_right), 151);
    let just_left = eye_point((150 - 120) * 256 + 127, z);
    assert_eq!(view.first_column_at_or_after(just_left), 150);
    // Two walls meeting at that vertex: the left one ends before 150, the right one starts at it.
    let left_wall = (
        view.first_column_at_or_after(eye_point(-(50 << 8), 100 << 8)),
        150,
    );
    let right_wall = (
        150,
        view.first_column_at_or_after(eye_point(60 << 8, 100 << 8)),
    );
    assert_eq!(view.first_column_at_or_after(on_centre), left_wall.1);
    assert_eq!((left_wall.0, right_wall.1), (60, 192)); // 60.0 → 60; 192.0 → 192
                                                        // Screen-space positions follow the same rule.
    assert_eq!(
        view.first_column_at_or_after_x(Fx16_16::from_bits(150 * 65536 + 32768)),
        150
    );
    assert_eq!(
        view.first_column_at_or_after_x(Fx16_16::from_bits(150 * 65536 + 32769)),
        151
    );
    assert_eq!(view.first_column_at_or_after_x(Fx16_16::from_int(-3)), 0);
    assert_eq!(view.first_column_at_or_after_x(Fx16_16::from_int(300)), 240);
    // The view axis (x = 120.0) is the left edge of column 120.
    assert_eq!(view.first_column_at_or_after(eye_point(0, 1)), 120);
    // The frustum edges at 45°: x = 0 and x = 240 exactly.
    assert_eq!(
        view.first_column_at_or_after(eye_point(-(500 << 8), 500 << 8)),
        0
    );
    assert_eq!(
        view.first_column_at_or_after(eye_point(500 << 8, 500 << 8)),
        240
    );
    assert_eq!(
        view.first_column_at_or_after(eye_point((500 << 8) - 1, 500 << 8)),
        240
    );
    assert_eq!(
        view.first_column_at_or_after(eye_point((500 << 8) - 200, 500 << 8)),
        240
    ); // 239.81
       // The centre of the last column, 239.5, at x' = 119.5, z' = 120; and one ulp to its right.
    assert_eq!(
        view.first_column_at_or_after(eye_point(30592, 120 << 8)),
        239
    );
    assert_eq!(
        view.first_column_at_or_after(eye_point(30593, 120 << 8)),
        240
    );
}

#[test]
fn extremes_of_the_declared_eye_space() {
    for (width, height) in SCREENS {
        let view = Viewport::new(width, height);
        let far = DEPTH_MAX_BITS;
        // Far off to the sides at the near plane: clamped to the screen edges.
        assert_eq!(
            view.first_column_at_or_after(eye_point(far, NEAR_DEPTH.to_bits())),
            width
        );
        assert_eq!(
            view.first_column_at_or_after(eye_point(-far, NEAR_DEPTH.to_bits())),
            0
        );
        assert_eq!(view.first_column_at_or_after(eye_point(far, 1)), width);
        // Saturation of the continuous position: d·x'/z' = 120·23171 ≫ 32768.
        assert_eq!(
            view.projected_x_saturating(eye_point(far, NEAR_DEPTH.to_bits())),
            Fx16_16::MAX
        );
        assert_eq!(
            view.projected_x_saturating(eye_point(-far, NEAR_DEPTH.to_bits())),
            Fx16_16::MIN
        );
        assert_eq!(view.projected_x_exact(eye_point(far, 1)), Fx16_16::MAX);
        // The farthest point straight ahead.
        assert_eq!(view.first_column_at_or_after(eye_point(0, far)), width / 2);
        assert_eq!(
            view.projected_x_exact(eye_point(0, far)),
            Fx16_16::from_int(width / 2)
        );
        // The approximate path is off by |x|·(1e-9 + 23171·2^-31) = 120 · 1.08e-5 here.
        let approx = view.projected_x_saturating(eye_point(0, far)) - Fx16_16::from_int(width / 2);
        assert!(
            approx.abs().to_bits() as f64 <= (width / 2) as f64 * 65536.0 * 1.08e-5 + 1.0,
            "{approx:?}"
        );
        // The highest wall at the near plane projects far off screen but inside 24.8.
        let y = view.projected_y(Fx24_8::from_int(HEIGHT_DIFF_MAX), Fx2_30::ONE);
        assert_eq!(
            y,
            Fx24_8::from_int(height / 2 - view.focal_y * HEIGHT_DIFF_MAX)
        );
        assert_eq!(view.first_row_at_or_after(y), 0);
        let y = view.projected_y(Fx24_8::from_int(-HEIGHT_DIFF_MAX), Fx2_30::ONE);
        assert_eq!(view.first_row_at_or_after(y), height);
    }
}

#[test]
fn viewports_of_the_four_screens() {
    let focal: Vec<(i32, i32, i32)> = SCREENS
        .iter()
        .map(|&(w, h)| Viewport::new(w, h))
        .map(|v| (v.focal_x, v.focal_y, v.horizon_y))
        .collect();
    assert_eq!(
        focal,
        [(120, 120, 80), (120, 60, 40), (60, 120, 80), (60, 60, 40)]
    );
}

#[test]
fn eye_frame_axes() {
    // Looking along +y (90°): forward is +y, right is −x.
    let frame = EyeFrame::new(WorldPoint::from_int(10, 20), Angle::QUARTER);
    assert_eq!(
        frame.to_eye(WorldPoint::from_int(10, 30)),
        EyePoint::new(Fx24_8::ZERO, Fx24_8::from_int(10))
    );
    assert_eq!(
        frame.to_eye(WorldPoint::from_int(5, 20)),
        EyePoint::new(Fx24_8::from_int(5), Fx24_8::ZERO)
    );
    assert_eq!(
        frame.to_world(EyePoint::new(Fx24_8::from_int(5), Fx24_8::from_int(10))),
        WorldPoint::from_int(5, 30)
    );
    // At 45°, sin = cos = 46341/65536: the diagonal point is dead ahead (x' = 0 exactly) at
    // z' = 200·46341/65536 = 141.4215 → 36204/256 = 141.421875 (true 141.42136).
    let frame = EyeFrame::new(WorldPoint::from_int(0, 0), Angle::EIGHTH);
    let q = frame.to_eye(WorldPoint::from_int(100, 100));
    assert_eq!(q.x, Fx24_8::ZERO);
    assert_eq!(q.z.to_bits(), 36204);
}

#[test]
fn near_plane_special_cases() {
    let near = NEAR_DEPTH.to_bits();
    // Ending exactly on the plane: kept whole.
    let a = eye_point(-(10 << 8), near);
    let b = eye_point(10 << 8, 50 << 8);
    let whole = clip_to_near_plane(a, b).unwrap();
    assert_eq!((whole.start, whole.end), (a, b));
    // One ulp in front of the plane on one side: a tiny cut at t ≈ 0.
    let behind = eye_point(-(10 << 8), near - 1);
    let cut = clip_to_near_plane(behind, b).unwrap();
    assert_eq!(cut.start.z, NEAR_DEPTH);
    assert!(cut.t_start.to_bits() > 0 && cut.t_start.to_bits() < 1 << 20);
    // Entirely behind, and running behind to in front through the eye.
    assert_eq!(
        clip_to_near_plane(eye_point(0, -5), eye_point(7, near - 1)),
        None
    );
    let through =
        clip_to_near_plane(eye_point(-(4 << 8), -(4 << 8)), eye_point(4 << 8, 4 << 8)).unwrap();
    assert_eq!(through.start, eye_point(near, near));
    assert_eq!(through.t_start, Fx2_30::from_bits(5 << 27)); // (1 + 4) / 8
}
