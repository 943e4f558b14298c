# Sourced by the ray tracer's image-comparison scripts (simd-compact.sh, simd-lanes.sh): render
# a scene's colour and depth under one environment setting, and compare two renders bit for bit.
# The sourcing script sets exe (rill-trace), work (its directory) and tag (its messages' prefix).

# render_outputs NAME SETTING SCENE ARGS...: rill-trace render SCENE ARGS with SETTING
# (VAR=value) in its environment, into $work/NAME.{png,pfm,depth.pfm}.
# (Shell functions share the caller's variables: these names are the helper's own.)
render_outputs() {
  ro_name=$1; ro_setting=$2; ro_scene=$3; shift 3
  env "$ro_setting" "$exe" render "$ro_scene" --quiet "$@" --out "$work/$ro_name.png" \
    --pfm "$work/$ro_name.pfm" --depth "$work/$ro_name.depth.pfm" > /dev/null
}

# same_outputs A B: the two renders' colour and depth are the same bytes, else exit 1.
same_outputs() {
  for so_ext in pfm depth.pfm; do
    if ! cmp -s "$work/$1.$so_ext" "$work/$2.$so_ext"; then
      echo "$tag: $1.$so_ext and $2.$so_ext differ"
      exit 1
    fi
  done
}
