//! Writes the shipped test image: `cargo run -p hodr-raster --example landscape -- OUT.png [SIZE]`.

fn main() -> Result<(), hodr_raster::Error> {
    let mut args = std::env::args().skip(1);
    let out = args.next().unwrap_or_else(|| "landscape.png".into());
    let size = args.next().and_then(|s| s.parse().ok()).unwrap_or(128);
    hodr_raster::test_image::landscape(size)?.save_png(&out)?;
    println!("wrote {out} ({size}×{size})");
    Ok(())
}
