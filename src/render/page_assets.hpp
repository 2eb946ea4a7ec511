#pragma once
// The report page's template, style sheet and script (private to render),
// compiled in from src/render/page/ by cmake/embed_text.cmake.
namespace hba::render {

extern const char* const kReportPageTemplate;  // report.html: {{TITLE}}, {{STYLE}}, ... filled in
extern const char* const kReportPageStyle;     // report.css
extern const char* const kReportPageScript;    // report.js

}  // namespace hba::render
