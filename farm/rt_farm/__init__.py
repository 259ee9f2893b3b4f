"""rt-farm: one render (or a range of frames) split into sample ranges, rendered as
tasks on a Ray cluster and merged by `rt merge` into the image one `rt render` gives,
bit for bit. See docs/farm.md."""
