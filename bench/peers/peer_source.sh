# Sourced by build_stage.sh and build_rvo2.sh: extracts a peer's source tree from a git URL or a
# local clone (a work tree or a bare repository) at a revision, and records the commit.
#
#   peer_source SOURCE REF DIR    # DIR/src: the tree at REF; DIR/commit: its commit id
peer_source() {
  local source=$1 ref=$2 dir=$3 git_dir
  rm -rf "$dir/src" "$dir/repo.git"
  mkdir -p "$dir/src"
  if git -C "$source" rev-parse --git-dir >/dev/null 2>&1; then
    git_dir=$(git -C "$source" rev-parse --absolute-git-dir)  # a local clone: read it in place
  else
    git clone --quiet --bare "$source" "$dir/repo.git"  # a URL: fetched once into DIR
    git_dir=$dir/repo.git
  fi
  git --git-dir="$git_dir" rev-parse --verify --quiet "$ref^{commit}" >"$dir/commit" || {
    echo "error: $source has no revision '$ref'" >&2
    return 2
  }
  git --git-dir="$git_dir" archive "$(cat "$dir/commit")" | tar -x -C "$dir/src"
}
