//! The numeric tables generated at build time by `portalcast_assets::numeric_tables`
//! (sine quarter wave, reciprocal seeds, small reciprocals). Their sizes and error analysis are
//! documented where they are used: [`super::angle`] and [`super::recip`].

include!(concat!(env!("OUT_DIR"), "/numeric_tables.rs"));
