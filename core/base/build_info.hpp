// What program made a file: sonarsim's version and the commit of its sources (core/base/build_info.cmake
// writes them at every build), for the provenance of datasets.
#pragma once

namespace sonarsim {

/// The project's version ("0.1.0").
const char* program_version();
/// The git commit the sources were built from (12 hex digits, "+changes" when the work tree differed from
/// it), or "unknown" when they were no git checkout.
const char* program_commit();

} // namespace sonarsim
