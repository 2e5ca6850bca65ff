/* The report as HTML (sphlab lesson N --export DIR --format html): a small
 * Markdown writer for the subset the report templates use -- headings,
 * paragraphs, lists, tables, fenced code, block quotes, and inline code,
 * bold, italic, images and links. The figures are linked, not embedded:
 * report.html sits beside them in DIR. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lesson.h"

static void esc(FILE *o, const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++) switch (s[i]) {
        case '<': fputs("&lt;", o); break;
        case '>': fputs("&gt;", o); break;
        case '&': fputs("&amp;", o); break;
        case '"': fputs("&quot;", o); break;
        default: fputc(s[i], o);
        }
}

/* A span [s, s + n): `code`, **bold**, *italic*, ![alt](src), [text](href). */
static void inl(FILE *o, const char *s, size_t n)
{
    size_t i = 0;
    while (i < n) {
        const char *c = s + i, *end = s + n;
        if (*c == '\\' && c + 1 < end && c[1] == '|') { /* an escaped bar inside a table cell */
            fputc('|', o);
            i += 2;
            continue;
        }
        if (*c == '`') {
            const char *q = memchr(c + 1, '`', (size_t)(end - c - 1));
            if (q) {
                fputs("<code>", o);
                esc(o, c + 1, (size_t)(q - c - 1));
                fputs("</code>", o);
                i = (size_t)(q + 1 - s);
                continue;
            }
        }
        if ((*c == '!' && c + 1 < end && c[1] == '[') || *c == '[') {
            bool img = *c == '!';
            const char *lb = c + img, *rb = memchr(lb, ']', (size_t)(end - lb));
            if (rb && rb + 1 < end && rb[1] == '(') {
                const char *rp = memchr(rb + 2, ')', (size_t)(end - rb - 2));
                if (rp) {
                    if (img) {
                        fputs("<img src=\"", o);
                        esc(o, rb + 2, (size_t)(rp - rb - 2));
                        fputs("\" alt=\"", o);
                        esc(o, lb + 1, (size_t)(rb - lb - 1));
                        fputs("\">", o);
                    } else {
                        fputs("<a href=\"", o);
                        esc(o, rb + 2, (size_t)(rp - rb - 2));
                        fputs("\">", o);
                        inl(o, lb + 1, (size_t)(rb - lb - 1));
                        fputs("</a>", o);
                    }
                    i = (size_t)(rp + 1 - s);
                    continue;
                }
            }
        }
        if (*c == '*') {
            bool bold = c + 1 < end && c[1] == '*';
            const char *mark = bold ? "**" : "*";
            size_t ml = bold ? 2 : 1;
            const char *q = c + ml;
            while (q < end && !(strncmp(q, mark, ml) == 0 && (bold || q[-1] != ' '))) q++;
            if (q < end && q > c + ml) {
                fputs(bold ? "<strong>" : "<em>", o);
                inl(o, c + ml, (size_t)(q - c - ml));
                fputs(bold ? "</strong>" : "</em>", o);
                i = (size_t)(q + ml - s);
                continue;
            }
        }
        esc(o, c, 1);
        i++;
    }
}

static bool table_row(const char *line)
{
    return line[0] == '|';
}

/* The next cell border: a '|' not escaped as "\|" (Markdown's way to put a
 * bar inside a cell). */
static const char *next_bar(const char *p)
{
    for (; *p; p++) {
        if (*p == '\\' && p[1] == '|') {
            p++;
            continue;
        }
        if (*p == '|') return p;
    }
    return NULL;
}

static void row(FILE *o, const char *line, const char *cell)
{
    fputs("<tr>", o);
    const char *p = line + 1;
    for (const char *q; (q = next_bar(p)); p = q + 1) {
        const char *a = p, *b = q;
        while (a < b && *a == ' ') a++;
        while (b > a && b[-1] == ' ') b--;
        fprintf(o, "<%s>", cell);
        inl(o, a, (size_t)(b - a));
        fprintf(o, "</%s>", cell);
    }
    fputs("</tr>\n", o);
}

void lx_html_write(const char *md, const char *title, const char *lang, FILE *o)
{
    fprintf(o, "<!DOCTYPE html>\n<html lang=\"%s\"><head><meta charset=\"utf-8\"><title>", lang);
    esc(o, title, strlen(title));
    fputs("</title>\n<style>body{font-family:sans-serif;max-width:60em;margin:2em auto;line-height:1.45}"
          "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:2px 6px}"
          "img{max-width:100%}pre{background:#f4f4f4;padding:6px;overflow-x:auto}</style>\n</head><body>\n",
          o);
    char *copy = strdup(md ? md : "");
    if (!copy) return;
    enum { NONE, PARA, LIST, TABLE, CODE, QUOTE } in = NONE;
    int table_rows = 0;
    for (char *line = copy, *next; line; line = next) {
        next = strchr(line, '\n');
        if (next) *next++ = '\0';
        if (in == CODE) {
            if (strncmp(line, "```", 3) == 0) {
                fputs("</code></pre>\n", o);
                in = NONE;
            } else {
                esc(o, line, strlen(line));
                fputc('\n', o);
            }
            continue;
        }
        const char *t = line;
        bool item = (t[0] == '-' || t[0] == '*') && t[1] == ' ';
        bool cont = in == LIST && (t[0] == ' ' && t[1] == ' ') && t[strspn(t, " ")];
        /* close what this line does not continue */
        if ((in == PARA && (!*t || item || t[0] == '#' || table_row(t) || t[0] == '>')) ||
            (in == LIST && !item && !cont && *t) || (in == TABLE && !table_row(t)) || (in == QUOTE && t[0] != '>')) {
            fputs(in == PARA ? "</p>\n" : in == LIST ? "</li></ul>\n" : in == TABLE ? "</table>\n" : "</blockquote>\n", o);
            in = NONE;
        }
        if (!*t) continue;
        if (strncmp(t, "```", 3) == 0) {
            if (in != NONE) fputs(in == PARA ? "</p>\n" : in == LIST ? "</li></ul>\n" : "", o);
            fputs("<pre><code>", o);
            in = CODE;
        } else if (t[0] == '#') {
            int lv = (int)strspn(t, "#");
            if (lv > 6) lv = 6;
            fprintf(o, "<h%d>", lv);
            const char *h = t + lv + (t[lv] == ' ');
            inl(o, h, strlen(h));
            fprintf(o, "</h%d>\n", lv);
        } else if (table_row(t)) {
            if (in != TABLE) {
                fputs("<table>\n", o);
                in = TABLE;
                table_rows = 0;
            }
            if (strspn(t, "|-: ") == strlen(t)) continue; /* the header's rule */
            row(o, t, table_rows++ == 0 ? "th" : "td");
        } else if (item) {
            fputs(in == LIST ? "</li><li>" : "<ul><li>", o);
            in = LIST;
            inl(o, t + 2, strlen(t + 2));
        } else if (cont) {
            const char *c = t + strspn(t, " ");
            fputs(strncmp(c, "![", 2) == 0 ? "<br>" : " ", o);
            inl(o, c, strlen(c));
        } else if (t[0] == '>') {
            if (in != QUOTE) fputs("<blockquote>", o);
            in = QUOTE;
            const char *q = t + 1 + (t[1] == ' ');
            inl(o, q, strlen(q));
            fputc('\n', o);
        } else {
            fputs(in == PARA ? "\n" : "<p>", o);
            in = PARA;
            inl(o, t, strlen(t));
        }
    }
    if (in != NONE)
        fputs(in == PARA   ? "</p>\n"
              : in == LIST ? "</li></ul>\n"
              : in == TABLE ? "</table>\n"
              : in == CODE  ? "</code></pre>\n"
                            : "</blockquote>\n",
              o);
    fputs("</body></html>\n", o);
    free(copy);
}
