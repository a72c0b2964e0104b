// A deliberate break of io/'s own order: its files folder must not include the report.
#pragma once

#include "floorgrid/io/report/report_html.hpp"
