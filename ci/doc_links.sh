#!/usr/bin/env bash
# Checks the documentation's links: every relative markdown link ([text](path), [text](path#anchor))
# and every `docs/...md` path mentioned in README.md, CONTRIBUTING.md and docs/**/*.md must name a
# file or folder of the checkout. Prints each one that does not, as FILE:LINE: TARGET, and exits 1;
# exits 0 when all exist. Web links (scheme:) and in-page anchors (#...) are not checked.
#   usage: bash ci/doc_links.sh
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
/usr/bin/env python3 - <<'EOF'
import glob
import os
import re
import sys

pages = ["README.md", "CONTRIBUTING.md"] + sorted(glob.glob("docs/**/*.md", recursive=True))
link = re.compile(r"\]\(([^)\s]+)\)")
mention = re.compile(r"(?<![\w/.-])(docs/[\w./-]*\.md)")
missing = []
for page in pages:
    base = os.path.dirname(page)
    fence = False
    with open(page, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if line.lstrip().startswith("```"):
                fence = not fence
            targets = []
            if not fence:
                for target in link.findall(line):
                    if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
                        continue
                    path = target.split("#", 1)[0]
                    if path:
                        targets.append((target, os.path.normpath(os.path.join(base, path))))
            for path in mention.findall(line):
                targets.append((path, path))
            for shown, path in targets:
                if not os.path.exists(path):
                    missing.append("%s:%d: %s" % (page, number, shown))
for m in missing:
    print(m)
if missing:
    print("ci/doc_links.sh: %d link(s) to missing files" % len(missing), file=sys.stderr)
    sys.exit(1)
print("ci/doc_links.sh: %d pages, every link resolves" % len(pages))
EOF
