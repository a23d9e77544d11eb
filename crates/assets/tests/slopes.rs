//! Sloped floors and ceilings in text maps: the planes the compiler stores, and what it
//! refuses (the bad maps `slope_*.map` in `tests/bad/`).

use portalcast_assets::{compile_map_str, Catalog};
use portalcast_format::{Plane, NO_SLOPE, PLANE_ERROR_BOUND_FX8};

fn catalog() -> Catalog {
    Catalog::new(["brick", "stone"], [] as [&str; 0], false)
}

/// A flat room `low`, a ramp `ramp` rising along +x from 0 to `rise` over 128 units, a flat
/// landing `top` at `rise`; the ramp's ceiling is `ceiling`.
fn ramp_map(floor_slope: &str, ceiling: &str) -> String {
    format!(
        "vertex a 0 0\nvertex b 128 0\nvertex c 256 0\nvertex d 384 0\n\
         vertex e 384 128\nvertex f 256 128\nvertex g 128 128\nvertex h 0 128\n\
         sector low floor=0 ceil=192 floor_tex=stone ceil_tex=stone\n\
         wall a b tex=brick\nwall b g portal=ramp lower=brick upper=brick\nwall g h tex=brick\nwall h a tex=brick\n\
         sector ramp {floor_slope} {ceiling} floor_tex=stone ceil_tex=stone\n\
         wall b c tex=brick\nwall c f portal=top lower=brick upper=brick\nwall f g tex=brick\n\
         wall g b portal=low lower=brick upper=brick\n\
         sector top floor=64 ceil=192 floor_tex=stone ceil_tex=stone\n\
         wall c d tex=brick\nwall d e tex=brick\nwall e f tex=brick\nwall f c portal=ramp lower=brick upper=brick\n\
         player 64 64\n"
    )
}

#[test]
fn a_ramp_s_plane_gives_its_corners_heights() {
    let map = compile_map_str(
        "ramp.map",
        &ramp_map("floor_slope=b:0,g:0,c:64,f:64", "ceil=192"),
        &catalog(),
    )
    .unwrap_or_else(|errors| panic!("{errors}"));
    let ramp = map.sectors[1];
    assert_eq!(map.sectors[0].slope, NO_SLOPE);
    assert_eq!(map.sectors[2].slope, NO_SLOPE);
    assert_eq!(ramp.slope, 0);
    assert_eq!(map.slopes.len(), 1);
    let planes = map.slopes[0];
    // z = (x − 128)/2: rise 1/2 per unit along x.
    assert_eq!(planes.floor.gradient_x_fx24, 1 << 23);
    assert_eq!(planes.floor.gradient_y_fx24, 0);
    assert_eq!(planes.floor.base_fx8, -64 * 256);
    assert_eq!(planes.ceiling, Plane::flat(192));
    assert_eq!((ramp.floor_z, ramp.ceil_z), (0, 192));
    let tables = map.tables();
    assert_eq!(
        tables.heights_fx8_at(&ramp, 192 * 256, 50 * 256),
        (32 * 256, 192 * 256)
    );
}

#[test]
fn a_sloped_ceiling_sets_the_sector_s_highest_ceiling_and_planes_are_shared() {
    let text = ramp_map("floor_slope=b:0,g:0,c:64", "ceil_slope=b:128,c:192,f:192");
    let map = compile_map_str("ramp.map", &text, &catalog()).unwrap_or_else(|e| panic!("{e}"));
    let ramp = map.sectors[1];
    assert_eq!((ramp.floor_z, ramp.ceil_z), (0, 192));
    assert_eq!(map.slopes[0].ceiling.gradient_x_fx24, 1 << 23);
}

#[test]
fn heights_off_the_grid_are_within_the_stated_bound() {
    // A plane through (128,0,0), (256,0,7), (128,128,3): gradients 7/128 and 3/128.
    let text = ramp_map("floor_slope=b:0,c:7,g:3", "ceil=192");
    let map = compile_map_str("ramp.map", &text, &catalog()).unwrap_or_else(|e| panic!("{e}"));
    let floor = map.slopes[0].floor;
    for (x, y) in [
        (128.0, 0.0),
        (256.0, 0.0),
        (128.0, 128.0),
        (256.0, 128.0),
        (200.5, 77.25),
    ] {
        let exact = 256.0 * ((x - 128.0) * 7.0 / 128.0 + y * 3.0 / 128.0);
        let got = f64::from(floor.height_fx8_at((x * 256.0) as i32, (y * 256.0) as i32));
        assert!(
            (got - exact).abs() <= f64::from(PLANE_ERROR_BOUND_FX8),
            "({x}, {y}): {got} against {exact}"
        );
    }
}
