# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Every ```python block of a page runs, in order, in one namespace, from the source folder:
#   python3 doc_blocks.py <page.md>...   (ctest python_docs)
import pathlib
import os
import sys
import traceback


def blocks(path):
    out, cur, start = [], None, 0
    for i, line in enumerate(path.read_text().splitlines(), 1):
        if cur is None and line.strip() == "```python":
            cur, start = [], i + 1
        elif cur is not None and line.startswith("```"):
            out.append((start, "\n".join(cur) + "\n"))
            cur = None
        elif cur is not None:
            cur.append(line)
    return out


def main():
    src = pathlib.Path(os.environ.get("DALEMBERT_SOURCE", pathlib.Path(__file__).parents[2]))
    pages = [pathlib.Path(p).resolve() for p in sys.argv[1:]]
    os.chdir(src)
    total = 0
    for page in pages:
        ns = {"__name__": "__doc__"}
        found = blocks(page)
        if not found:
            print(f"{page}: no python blocks", file=sys.stderr)
            return 1
        for line, code in found:
            try:
                exec(compile(code, f"{page}:{line}", "exec"), ns)
            except Exception:
                traceback.print_exc()
                print(f"{page}:{line}: the block failed", file=sys.stderr)
                return 1
            total += 1
    print(f"doc_blocks.py: {total} python blocks ran")
    return 0


if __name__ == "__main__":
    sys.exit(main())
