"""Every relative link and picture in README.md and docs/ leads somewhere: the file exists, and
a #fragment names a heading of that file as GitHub makes anchors of headings. Usage:
doc_links_check.py REPOSITORY. Prints each broken link with its file and line; exits 1 if any.
"""
import pathlib
import re
import sys

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
HEADING = re.compile(r"^#{1,6} (.*)$")


def outside_code(lines):
    """(number, line) of the lines outside fenced code blocks."""
    fenced = False
    for number, line in enumerate(lines, 1):
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced:
            yield number, line


def anchor(heading):
    """GitHub's anchor for a heading: lower case, code marks and punctuation dropped, spaces as
    hyphens."""
    text = heading.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors_of(path):
    lines = path.read_text(encoding="utf-8").splitlines()
    return {anchor(match.group(1)) for _, line in outside_code(lines) if (match := HEADING.match(line))}


def broken_links(repository):
    pages = [repository / "README.md", *sorted((repository / "docs").rglob("*.md"))]
    for page in pages:
        lines = page.read_text(encoding="utf-8").splitlines()
        for number, line in outside_code(lines):
            for target in LINK.findall(re.sub(r"`[^`]*`", "", line)):
                if re.match(r"[a-z]+:", target):
                    continue  # a web address: not checked here
                file_part, _, fragment = target.partition("#")
                destination = (page.parent / file_part).resolve() if file_part else page
                where = f"{page.relative_to(repository)}:{number}: {target}"
                if not destination.exists():
                    yield f"{where}: no such file"
                elif fragment and destination.suffix == ".md" and fragment not in anchors_of(destination):
                    yield f"{where}: no heading with this anchor in {destination.name}"


def main():
    repository = pathlib.Path(sys.argv[1]).resolve()
    broken = list(broken_links(repository))
    for problem in broken:
        print(problem)
    checked = "README.md and docs/"
    print(f"{len(broken)} broken links in {checked}" if broken else f"every link in {checked} leads somewhere")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
