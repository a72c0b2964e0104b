// A deliberate break of io/'s layout: a header right in io/, outside its concept folders.
#pragma once
