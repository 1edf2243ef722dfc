# Sourced by the whole-scene scripts (scene_reports.sh, parallel_reports.sh): what a bundled
# scene holds, read from its YAML without a YAML parser.

# The names of a scene's paths (its `paths:` list), one per line.
paths_of() {
  awk '/^paths:/{p=1;next} p&&/^[a-z]/{p=0} p&&/name:/{sub(/.*name: */,"");sub(/[,} ].*/,"");print}' "$1"
}

# The scene's head (`head: rs535`, `head: afp`, ...).
head_of() {
  awk '/^head:/{print $2; exit}' "$1"
}
