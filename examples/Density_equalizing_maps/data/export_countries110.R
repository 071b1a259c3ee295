# Exports Natural Earth 1:110m admin-0 countries, as shipped by the Debian package
# r-cran-rnaturalearthdata, to countries110.geojson and their population
# estimates to population.csv (see README.md). Needs only R and r-cran-sp:
#   Rscript export_countries110.R
# Rings are written in RFC 7946 order: exterior rings counterclockwise, holes
# clockwise (in the longitude/latitude plane), first position repeated last.
suppressMessages(library(sp))
data(countries110, package = "rnaturalearthdata")
x <- countries110
# Western Sahara has no population estimate (NA) in this version: left out, so
# that every exported region has a value (its land is counted as sea).
x <- x[!is.na(x@data$pop_est), ]
d <- x@data
id <- as.character(d$adm0_a3)
stopifnot(!anyDuplicated(id))
fmt <- function(v) sub("\\.?0+$", "", sprintf("%.4f", v))
ring_json <- function(xy, hole) {
  a <- sum(xy[-nrow(xy), 1] * xy[-1, 2] - xy[-1, 1] * xy[-nrow(xy), 2]) / 2
  if((a > 0) == hole) xy <- xy[nrow(xy):1, , drop = FALSE]
  paste0("[", paste0("[", fmt(xy[, 1]), ",", fmt(xy[, 2]), "]", collapse = ","), "]")
}
esc <- function(s) gsub('"', '\\\\"', s)
features <- character(0)
for(k in seq_len(nrow(d))) {
  rings <- x@polygons[[k]]@Polygons
  # group: each exterior ring with the holes that lie in it (sp keeps them in order)
  polys <- list()
  for(r in rings) {
    xy <- r@coords
    if(!r@hole) polys[[length(polys) + 1]] <- ring_json(xy, FALSE)
    else {
      polys[[length(polys)]] <- c(polys[[length(polys)]], ring_json(xy, TRUE))
    }
  }
  geom <- paste0('{"type":"MultiPolygon","coordinates":[',
                 paste0(sapply(polys, function(p) paste0("[", paste(p, collapse = ","), "]")), collapse = ","), "]}")
  props <- sprintf('{"adm0_a3":"%s","name":"%s","continent":"%s","pop_est":%.0f}', id[k], esc(as.character(d$admin[k])),
                   esc(as.character(d$continent[k])), d$pop_est[k])
  features <- c(features, sprintf('{"type":"Feature","properties":%s,"geometry":%s}', props, geom))
}
writeLines(paste0('{"type":"FeatureCollection","features":[\n', paste(features, collapse = ",\n"), "\n]}"),
           "countries110.geojson")
csv <- data.frame(adm0_a3 = id, name = as.character(d$admin), pop_est = sprintf("%.0f", d$pop_est))
csv$name <- paste0('"', gsub('"', '""', csv$name), '"')
writeLines(c("adm0_a3,name,pop_est", paste(csv$adm0_a3, csv$name, csv$pop_est, sep = ",")), "population.csv")
