// Replaced by the report page (lead placeholder while the page is written).
(function () {
  const data = JSON.parse(document.getElementById('stitchsim-data').textContent);
  document.getElementById('app').textContent = data.summary.verdict;
  window.stitchsimReady = true;
})();
